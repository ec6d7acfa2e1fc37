#include "pbms/io/yaml_file.hpp"

#include <fstream>

#include <fmt/format.h>

#include "pbms/error.hpp"

namespace pbms {

std::string yaml_text(const YAML::Node& node) {
  YAML::Emitter e;
  e.SetDoublePrecision(17);
  e << node;
  return e.c_str();
}

void write_yaml_atomic(const std::filesystem::path& path, const YAML::Node& node,
                       const std::string& header_comment) {
  const auto tmp = path.string() + ".tmp";
  {
    std::ofstream out(tmp);
    if (!out) throw Error(fmt::format("cannot write '{}'", tmp));
    if (!header_comment.empty()) out << "# " << header_comment << "\n";
    YAML::Emitter e;
    e.SetDoublePrecision(10);
    e << node;
    out << e.c_str() << "\n";
    out.flush();
    if (!out) throw Error(fmt::format("writing '{}' failed (disk full?)", tmp));
  }
  std::filesystem::rename(tmp, path);
}

}  // namespace pbms
