#include "earlier_run.hpp"

#include <fmt/format.h>

#include "pbms/error.hpp"
#include "pbms/io/hdf5.hpp"
#include "pbms/io/yaml_file.hpp"

namespace pbms::coupler {
namespace {

YAML::Node load_if_there(const std::filesystem::path& file) {
  if (!std::filesystem::exists(file)) return YAML::Node(YAML::NodeType::Map);
  try {
    return YAML::LoadFile(file.string());
  } catch (const std::exception& e) {
    throw Error(fmt::format("{}: cannot be read to resume from: {}", file.string(), e.what()));
  }
}

std::string read_string_attribute(hid_t obj, const char* name) {
  if (H5Aexists(obj, name) <= 0) return {};
  h5::Handle a(H5Aopen(obj, name, H5P_DEFAULT), H5Aclose);
  h5::Handle type(H5Aget_type(a.id()), H5Tclose);
  // Read in the file's own string type: units are UTF-8 ("Å"), and HDF5
  // converts no string between character sets.
  if (H5Tis_variable_str(type.id()) > 0) {
    char* text = nullptr;
    if (H5Aread(a.id(), type.id(), &text) < 0 || !text) return {};
    std::string out(text);
    H5free_memory(text);
    return out;
  }
  std::string out(H5Tget_size(type.id()), '\0');
  if (H5Aread(a.id(), type.id(), out.data()) < 0) return {};
  out.resize(out.find('\0') == std::string::npos ? out.size() : out.find('\0'));
  return out;
}

std::vector<std::string> member_names(hid_t group) {
  H5G_info_t info{};
  H5Gget_info(group, &info);
  std::vector<std::string> out;
  // Name order: results.h5 is written without creation order, and a
  // reference finds a table or column by its name.
  for (hsize_t k = 0; k < info.nlinks; ++k) {
    const ssize_t len =
        H5Lget_name_by_idx(group, ".", H5_INDEX_NAME, H5_ITER_INC, k, nullptr, 0, H5P_DEFAULT);
    std::string name(static_cast<std::size_t>(std::max<ssize_t>(len, 0)), '\0');
    H5Lget_name_by_idx(group, ".", H5_INDEX_NAME, H5_ITER_INC, k, name.data(), name.size() + 1,
                       H5P_DEFAULT);
    out.push_back(name);
  }
  return out;
}

// Each subgroup of the stage's group is a table of 1-D columns.
void read_tables(const std::filesystem::path& file, const std::string& stage, StageResults& r) {
  if (!std::filesystem::exists(file)) return;
  h5::Handle f(H5Fopen(file.string().c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  if (H5Lexists(f.id(), stage.c_str(), H5P_DEFAULT) <= 0) return;
  h5::Handle g(H5Gopen2(f.id(), stage.c_str(), H5P_DEFAULT), H5Gclose);
  for (const auto& table : member_names(g.id())) {
    H5O_info_t oi{};
    if (H5Oget_info_by_name(g.id(), table.c_str(), &oi, H5P_DEFAULT) < 0 ||
        oi.type != H5O_TYPE_GROUP) {
      continue;
    }
    h5::Handle t(H5Gopen2(g.id(), table.c_str(), H5P_DEFAULT), H5Gclose);
    for (const auto& column : member_names(t.id())) {
      h5::Handle ds(H5Dopen2(t.id(), column.c_str(), H5P_DEFAULT), H5Dclose);
      h5::Handle space(H5Dget_space(ds.id()), H5Sclose);
      const hssize_t n = H5Sget_simple_extent_npoints(space.id());
      std::vector<double> data(static_cast<std::size_t>(std::max<hssize_t>(n, 0)));
      if (!data.empty() &&
          H5Dread(ds.id(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data()) < 0) {
        throw Error(fmt::format("{}: cannot read {}/{}/{}", file.string(), stage, table, column));
      }
      r.add_column(table, column, read_string_attribute(ds.id(), "unit"), std::move(data));
    }
  }
}

std::string scalar_text(const YAML::Node& n) {
  if (!n.IsDefined() || n.IsNull()) return "(not given)";
  if (n.IsScalar()) return fmt::format("'{}'", n.Scalar());
  return n.IsMap() ? "a map" : "a list";
}

std::string difference_at(const YAML::Node& a, const YAML::Node& b, const std::string& path) {
  const auto describe = [&] {
    return fmt::format("{}: {} in the earlier run, {} now", path.empty() ? "<document>" : path,
                       scalar_text(a), scalar_text(b));
  };
  // A key the one config has and the other lacks reads as a node that
  // yaml-cpp marks invalid; its Type() would throw instead of naming it.
  if (!a.IsDefined() || !b.IsDefined()) {
    return a.IsDefined() == b.IsDefined() ? std::string() : describe();
  }
  if (a.Type() != b.Type()) return describe();
  if (a.IsScalar()) return a.Scalar() == b.Scalar() ? std::string() : describe();
  if (a.IsSequence()) {
    if (a.size() != b.size()) {
      return fmt::format("{}: {} entries in the earlier run, {} now", path, a.size(), b.size());
    }
    for (std::size_t k = 0; k < a.size(); ++k) {
      auto d = difference_at(a[k], b[k], fmt::format("{}[{}]", path, k));
      if (!d.empty()) return d;
    }
    return {};
  }
  if (!a.IsMap()) return {};
  // Where the run lies and how many ranks it takes may change: a run
  // directory can be moved, a resume can take other ranks.
  const auto skipped = [&](const std::string& key) {
    return (path.empty() && key == "launch") ||
           (path == "run" && (key == "name" || key == "output"));
  };
  for (const auto& kv : a) {
    const std::string key = kv.first.Scalar();
    if (skipped(key)) continue;
    auto d = difference_at(kv.second, b[key], path.empty() ? key : fmt::format("{}.{}", path, key));
    if (!d.empty()) return d;
  }
  for (const auto& kv : b) {
    const std::string key = kv.first.Scalar();
    if (skipped(key)) continue;
    if (!a[key])
      return difference_at(YAML::Node(), kv.second,
                           path.empty() ? key : fmt::format("{}.{}", path, key));
  }
  return {};
}

}  // namespace

std::optional<EarlierRun> EarlierRun::read(const std::filesystem::path& dir) {
  if (!std::filesystem::exists(dir / "manifest.yaml")) return std::nullopt;
  EarlierRun r;
  r.dir_ = dir;
  r.manifest_ = load_if_there(dir / "manifest.yaml");
  r.summary_ = load_if_there(dir / "summary.yaml");
  r.config_ = load_if_there(dir / "config.yaml");
  return r;
}

YAML::Node EarlierRun::stage_entry(const std::string& stage) const {
  for (const auto& s : manifest_["stages"]) {
    if (s["name"] && s["name"].Scalar() == stage) return s;
  }
  return YAML::Node();
}

bool EarlierRun::finished(const std::string& stage) const {
  const YAML::Node s = stage_entry(stage);
  const YAML::Node sum = summary_["stages"][stage];
  return s.IsMap() && s["status"] && s["status"].Scalar() == "ok" && sum.IsMap() &&
         sum["results"].IsMap();
}

StageResults EarlierRun::results_of(const std::string& stage) const {
  StageResults r;
  for (const auto& kv : summary_["stages"][stage]["results"]) {
    const YAML::Node& v = kv.second;
    r.add_scalar(kv.first.Scalar(), v["value"].as<double>(), v["unit"].as<std::string>(""),
                 v["std_error"] ? v["std_error"].as<double>() : std::nan(""));
  }
  read_tables(dir_ / "results.h5", stage, r);
  const YAML::Node entry = stage_entry(stage);
  for (const auto& f : entry["files"]) r.files.push_back(f.as<std::string>());
  for (const auto& w : entry["warnings"]) r.warnings.push_back(w.as<std::string>());
  return r;
}

std::string first_difference(const YAML::Node& then, const YAML::Node& now) {
  return difference_at(then, now, "");
}

}  // namespace pbms::coupler
