#include "result_cache.hpp"

#include <unistd.h>

#include <cstdint>
#include <fstream>
#include <iterator>
#include <set>
#include <sstream>

#include <fmt/format.h>

#include "pbms/error.hpp"

namespace pbms::coupler {
namespace fs = std::filesystem;
namespace {

constexpr uint64_t kFnvOffset = 0xcbf29ce484222325ULL;
constexpr uint64_t kFnvPrime = 0x100000001b3ULL;

uint64_t fnv1a(const char* data, size_t n, uint64_t h = kFnvOffset) {
  for (size_t i = 0; i < n; ++i) {
    h ^= static_cast<unsigned char>(data[i]);
    h *= kFnvPrime;
  }
  return h;
}

std::optional<std::string> read_all(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) return std::nullopt;
  return std::string(std::istreambuf_iterator<char>(in), {});
}

void write_all(const fs::path& file, const void* data, size_t n) {
  std::ofstream out(file, std::ios::binary);
  out.write(static_cast<const char*>(data), static_cast<std::streamsize>(n));
  if (!out) throw Error(fmt::format("cannot write {}", file.string()));
}

// What a stage wrote, relative to the run directory: everything under
// <run_dir>/<stage>/ and whatever else its results list.
std::set<fs::path> files_of(const protocol::StageDone& done, const fs::path& run_dir) {
  std::set<fs::path> out;
  for (const auto& f : done.results.files) out.insert(f);
  const fs::path stage_dir = run_dir / done.stage;
  if (fs::is_directory(stage_dir)) {
    for (const auto& e : fs::recursive_directory_iterator(stage_dir)) {
      if (e.is_regular_file()) out.insert(fs::relative(e.path(), run_dir));
    }
  }
  return out;
}

}  // namespace

std::string file_digest(const fs::path& file) {
  const auto bytes = read_all(file);
  return bytes ? fmt::format("{:016x}", fnv1a(bytes->data(), bytes->size())) : std::string();
}

std::string cache_identity(const protocol::RunStage& request,
                           const std::vector<std::string>& software,
                           const std::string& driver_digest,
                           const std::vector<std::string>& input_files) {
  std::ostringstream s;
  s << "stage: " << request.name << "\nkind: " << request.kind << "\nseed: " << request.seed
    << "\ndriver: " << driver_digest << "\nsoftware: ["
    << fmt::format("{}", fmt::join(software, ", ")) << "]\nparams:\n"
    << request.params_yaml << "\nmaterials:\n"
    << request.materials_yaml << "\nfiles:\n";
  for (const auto& f : input_files) s << "  " << f << "\n";
  return s.str();
}

fs::path ResultCache::entry_dir(const std::string& identity) const {
  return dir_ / fmt::format("{:016x}", fnv1a(identity.data(), identity.size()));
}

std::optional<protocol::StageDone> ResultCache::find(const std::string& identity,
                                                     const fs::path& run_dir) const {
  const fs::path entry = entry_dir(identity);
  // The digest only names the entry; the full identity decides.
  if (read_all(entry / "identity.txt") != identity) return std::nullopt;
  const auto bytes = read_all(entry / "answer.bin");
  if (!bytes) return std::nullopt;
  protocol::StageDone done;
  try {
    auto m = protocol::unpack(reinterpret_cast<const std::byte*>(bytes->data()), bytes->size());
    done = std::get<protocol::StageDone>(std::move(m));
  } catch (const std::exception&) {
    return std::nullopt;  // another protocol version, or damage: compute again
  }
  std::error_code ec;
  fs::copy(entry / "files", run_dir,
           fs::copy_options::recursive | fs::copy_options::overwrite_existing, ec);
  if (ec) return std::nullopt;
  return done;
}

void ResultCache::store(const std::string& identity, const protocol::StageDone& done,
                        const fs::path& run_dir) const {
  const fs::path entry = entry_dir(identity);
  const fs::path aside = entry.string() + fmt::format(".part{}", ::getpid());
  fs::remove_all(aside);
  fs::create_directories(aside / "files");
  write_all(aside / "identity.txt", identity.data(), identity.size());
  const auto bytes = protocol::pack(done);
  write_all(aside / "answer.bin", bytes.data(), bytes.size());
  for (const auto& f : files_of(done, run_dir)) {
    fs::create_directories((aside / "files" / f).parent_path());
    fs::copy_file(run_dir / f, aside / "files" / f);
  }
  // An entry with another identity under the same digest is replaced: the
  // cache keeps one result per digest.
  fs::remove_all(entry);
  fs::rename(aside, entry);
}

}  // namespace pbms::coupler
