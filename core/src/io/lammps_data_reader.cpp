#include "pbms/io/lammps_data_reader.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <map>
#include <numeric>
#include <optional>
#include <string_view>
#include <vector>

#include <fmt/format.h>

#include "pbms/error.hpp"

namespace pbms {
namespace {

std::string_view trim(std::string_view s) {
  const auto first = s.find_first_not_of(" \t\r\n");
  if (first == std::string_view::npos) return {};
  return s.substr(first, s.find_last_not_of(" \t\r\n") - first + 1);
}

std::vector<std::string_view> split(std::string_view s) {
  std::vector<std::string_view> out;
  size_t i = 0;
  while (i < s.size()) {
    while (i < s.size() && std::isspace(static_cast<unsigned char>(s[i]))) ++i;
    const size_t start = i;
    while (i < s.size() && !std::isspace(static_cast<unsigned char>(s[i]))) ++i;
    if (i > start) out.push_back(s.substr(start, i - start));
  }
  return out;
}

std::string join(const std::vector<std::string_view>& tokens, size_t from) {
  std::string out;
  for (size_t i = from; i < tokens.size(); ++i) {
    if (i > from) out += ' ';
    out += tokens[i];
  }
  return out;
}

struct Section {
  int line = 0;  // of the section keyword
  size_t rows = 0;
};

class DataParser {
 public:
  explicit DataParser(std::string path) : path_(std::move(path)) {}

  ParticleSnapshot parse() {
    std::ifstream in(path_);
    if (!in) throw Error(fmt::format("{}: cannot open the LAMMPS data file", path_));
    std::string raw;
    std::getline(in, raw);  // the first line is a title, whatever it holds
    int number = 1;
    while (std::getline(in, raw)) {
      ++number;
      const auto hash = raw.find('#');
      const std::string_view all(raw);
      const auto text = trim(all.substr(0, hash));
      const auto comment = hash == std::string::npos ? std::string_view{} : all.substr(hash + 1);
      if (text.empty()) continue;
      line_ = number;
      if (std::isalpha(static_cast<unsigned char>(text.front()))) {
        begin_section(text, comment);
      } else if (section_.empty()) {
        header(split(text));
      } else {
        row(split(text));
      }
    }
    return finish();
  }

 private:
  [[noreturn]] void fail(int line, const std::string& what) const {
    throw Error(fmt::format("{}:{}: {}", path_, line, what));
  }
  [[noreturn]] void fail(const std::string& what) const { fail(line_, what); }

  std::int64_t integer(std::string_view tok, const char* what) const {
    if (!tok.empty() && tok.front() == '+') tok.remove_prefix(1);
    std::int64_t v = 0;
    const auto [end, ec] = std::from_chars(tok.data(), tok.data() + tok.size(), v);
    if (ec != std::errc() || end != tok.data() + tok.size()) {
      fail(fmt::format("cannot read '{}' as an integer ({})", tok, what));
    }
    return v;
  }

  double real(std::string_view tok, const char* what) const {
    if (!tok.empty() && tok.front() == '+') tok.remove_prefix(1);
    double v = 0;
    const auto [end, ec] = std::from_chars(tok.data(), tok.data() + tok.size(), v);
    if (ec != std::errc() || end != tok.data() + tok.size() || !std::isfinite(v)) {
      fail(fmt::format("cannot read '{}' as a finite number ({})", tok, what));
    }
    return v;
  }

  void header(const std::vector<std::string_view>& t) {
    const std::string keyword = join(t, 1);
    if (keyword == "atoms") {
      n_atoms_ = integer(t[0], "atom count");
      if (*n_atoms_ < 0) fail("the atom count is negative");
      atoms_line_ = line_;
      return;
    }
    if (keyword == "atom types") {
      n_types_ = integer(t[0], "atom type count");
      if (n_types_ < 1) fail("'atom types' must be at least 1");
      return;
    }
    if (t.size() == 6 && join(t, 3) == "xy xz yz") {
      fail("tilt factors 'xy xz yz': triclinic boxes are not supported");
    }
    for (int a = 0; a < 3; ++a) {
      const char axis = static_cast<char>('x' + a);
      if (t.size() == 4 && t[2] == fmt::format("{}lo", axis) && t[3] == fmt::format("{}hi", axis)) {
        lo_[a] = real(t[0], "box bound");
        hi_[a] = real(t[1], "box bound");
        if (!(hi_[a] > lo_[a])) fail(fmt::format("{}hi must exceed {}lo", axis, axis));
        return;
      }
    }
    // Counts of what atom_style atomic has none of (bonds, ellipsoids, ...)
    // are harmless when zero.
    std::int64_t count = -1;
    const auto [end, ec] = std::from_chars(t[0].data(), t[0].data() + t[0].size(), count);
    const bool is_count = ec == std::errc() && end == t[0].data() + t[0].size() && t.size() >= 2;
    if (is_count && count == 0) return;
    fail(fmt::format("header line '{}' is not supported (atom_style atomic only)", join(t, 0)));
  }

  void begin_section(std::string_view name, std::string_view comment) {
    const std::string s(name);
    if (s == "Atoms") {
      const auto style = split(comment);
      if (!style.empty() && style[0] != "atomic") {
        fail(fmt::format("atom style '{}' is not supported (atomic only)", style[0]));
      }
    } else if (s != "Masses" && s != "Velocities" && s != "Pair Coeffs" && s != "PairIJ Coeffs") {
      fail(
          fmt::format("section '{}' is not supported (atom_style atomic: Masses, Atoms, "
                      "Velocities)",
                      s));
    }
    if (sections_.count(s)) {
      fail(fmt::format("second '{}' section (the first is on line {})", s, sections_[s].line));
    }
    if (!n_atoms_) fail(fmt::format("section '{}' before the header's 'atoms' line", s));
    sections_[s].line = line_;
    section_ = s;
  }

  int type_of(std::string_view tok) const {
    if (n_types_ == 0) fail("the header has no 'atom types' line");
    const auto t = integer(tok, "atom type");
    if (t < 1 || t > n_types_) {
      fail(fmt::format("atom type {} is outside 1..{} (the header's atom types)", t, n_types_));
    }
    return static_cast<int>(t);
  }

  void row(const std::vector<std::string_view>& t) {
    ++sections_[section_].rows;
    if (section_ == "Atoms") {
      if (t.size() != 5 && t.size() != 8) {
        fail(fmt::format("Atoms line needs 5 or 8 columns, got {}", t.size()));
      }
      const auto id = integer(t[0], "atom id");
      if (id < 1) fail(fmt::format("atom id {} is not positive", id));
      const auto [it, fresh] = atom_line_.emplace(id, line_);
      if (!fresh) fail(fmt::format("atom id {} appears twice (also on line {})", id, it->second));
      snap_.id.push_back(id);
      snap_.species.push_back(type_of(t[1]) - 1);
      snap_.x.push_back({real(t[2], "x"), real(t[3], "y"), real(t[4], "z")});
      std::array<int, 3> image{0, 0, 0};
      if (t.size() == 8) {
        has_images_ = true;
        for (int a = 0; a < 3; ++a) image[a] = static_cast<int>(integer(t[5 + a], "image flag"));
      }
      snap_.image.push_back(image);
    } else if (section_ == "Velocities") {
      if (t.size() != 4) fail(fmt::format("Velocities line needs 4 columns, got {}", t.size()));
      const auto id = integer(t[0], "atom id");
      const auto [it, fresh] = velocity_.emplace(
          id, Velocity{line_, {real(t[1], "vx"), real(t[2], "vy"), real(t[3], "vz")}});
      if (!fresh) {
        fail(fmt::format("velocity of atom id {} given twice (also on line {})", id,
                         it->second.line));
      }
    } else if (section_ == "Masses") {
      if (t.size() != 2) fail(fmt::format("Masses line needs 2 columns, got {}", t.size()));
      const int type = type_of(t[0]);
      const double m = real(t[1], "mass");
      if (!(m > 0)) fail(fmt::format("mass {} of type {} is not positive", m, type));
      snap_.mass_per_type.resize(static_cast<size_t>(n_types_), 0.0);
      if (snap_.mass_per_type[type - 1] > 0) fail(fmt::format("mass of type {} given twice", type));
      snap_.mass_per_type[type - 1] = m;
    }
  }

  ParticleSnapshot finish() {
    if (!n_atoms_) fail(line_, "the header has no 'atoms' line");
    const auto find_section = [&](const char* s) -> std::optional<Section> {
      if (!sections_.count(s)) return std::nullopt;
      return sections_.at(s);
    };
    const auto atoms = find_section("Atoms");
    if (!atoms && *n_atoms_ > 0) {
      fail(atoms_line_,
           fmt::format("the header says {} atoms but there is no Atoms section", *n_atoms_));
    }
    if (atoms && static_cast<std::int64_t>(atoms->rows) != *n_atoms_) {
      fail(atoms->line,
           fmt::format("Atoms section has {} lines, the header (line {}) says {} atoms",
                       atoms->rows, atoms_line_, *n_atoms_));
    }
    if (const auto masses = find_section("Masses")) {
      if (static_cast<std::int64_t>(masses->rows) != n_types_) {
        fail(masses->line, fmt::format("Masses section has {} lines, the header says {} atom types",
                                       masses->rows, n_types_));
      }
    }
    const auto velocities = find_section("Velocities");
    if (velocities) {
      if (static_cast<std::int64_t>(velocities->rows) != *n_atoms_) {
        fail(velocities->line,
             fmt::format("Velocities section has {} lines, the header (line {}) says {} atoms",
                         velocities->rows, atoms_line_, *n_atoms_));
      }
      for (const auto& [id, v] : velocity_) {
        if (!atom_line_.count(id)) {
          fail(v.line,
               fmt::format("velocity of atom id {}, which is not in the Atoms section", id));
        }
      }
    }

    const size_t n = snap_.id.size();
    std::vector<size_t> order(n);
    std::iota(order.begin(), order.end(), size_t{0});
    std::sort(order.begin(), order.end(),
              [&](size_t a, size_t b) { return snap_.id[a] < snap_.id[b]; });
    ParticleSnapshot out;
    out.id.resize(n);
    out.species.resize(n);
    out.x.resize(n);
    out.v.assign(n, {0.0, 0.0, 0.0});
    if (has_images_) out.image.resize(n);
    for (size_t i = 0; i < n; ++i) {
      const size_t k = order[i];
      out.id[i] = snap_.id[k];
      out.species[i] = snap_.species[k];
      out.x[i] = snap_.x[k];
      if (has_images_) out.image[i] = snap_.image[k];
      if (velocities) out.v[i] = velocity_.at(out.id[i]).v;
    }
    out.has_velocities = velocities.has_value();
    out.box_lo = lo_;
    out.box_hi = hi_;
    out.periodic = {true, true, true};
    out.mass_per_type = std::move(snap_.mass_per_type);
    return out;
  }

  struct Velocity {
    int line;
    std::array<double, 3> v;
  };

  std::string path_;
  int line_ = 1;
  std::optional<std::int64_t> n_atoms_;
  int atoms_line_ = 0;
  std::int64_t n_types_ = 0;
  std::array<double, 3> lo_{-0.5, -0.5, -0.5}, hi_{0.5, 0.5, 0.5};
  std::string section_;
  std::map<std::string, Section> sections_;
  std::map<std::int64_t, int> atom_line_;
  std::map<std::int64_t, Velocity> velocity_;
  bool has_images_ = false;
  ParticleSnapshot snap_;  // in file order until finish()
};

}  // namespace

ParticleSnapshot read_lammps_data(const std::string& path) {
  return DataParser(path).parse();
}

}  // namespace pbms
