#include "kernels/pair_style_registry.hpp"

#include <map>
#include <utility>

#include "kernels/lj_nm.hpp"
#include "kernels/morse.hpp"
#include "kernels/pair_table.hpp"
#include "kernels/sutton_chen.hpp"
#include "pbms/error.hpp"

namespace pbms::dpd {

namespace {

// Built-ins are listed here rather than self-registering from their own files:
// static-initialiser registration is silently dropped when a static library's
// object file has no other referenced symbol.
struct Entry {
  PairStyleFactory create;
  std::vector<config::Param> params;
  std::string doc;
};

template <class Style>
std::pair<const std::string, Entry> entry() {
  return {std::string(Style::kStyle), {&Style::create, Style::params(), std::string(Style::kDoc)}};
}

std::map<std::string, Entry, std::less<>>& factories() {
  static std::map<std::string, Entry, std::less<>> table = {
      entry<Morse>(),
      entry<LjNm>(),
      entry<PairTable>(),
      entry<SuttonChen>(),
  };
  return table;
}

}  // namespace

std::unique_ptr<PairStyle> PairStyleRegistry::create(std::string_view style,
                                                     const PairStyleParameters& params) {
  const auto& table = factories();
  const auto it = table.find(style);
  if (it == table.end()) {
    std::string known;
    for (const auto& name : names()) known += (known.empty() ? "" : ", ") + name;
    throw Error("unknown pair style '" + std::string(style) + "'; known styles: " + known);
  }
  return it->second.create(params);
}

std::vector<std::string> PairStyleRegistry::names() {
  std::vector<std::string> out;
  for (const auto& [name, factory] : factories()) out.push_back(name);
  return out;
}

bool PairStyleRegistry::contains(std::string_view style) {
  return factories().find(style) != factories().end();
}

config::Param PairStyleRegistry::schema() {
  config::Param potential = config::Param::map(
      "potential",
      {config::Param::choice("style", names(), "Conservative force style of the DPD engine")
           .require()},
      "Conservative interaction of the mesoparticles; a potential file holds this same map");
  potential.discriminated_by("style");
  for (const auto& [name, e] : factories()) potential.variant(name, e.params, e.doc);
  return potential;
}

void PairStyleRegistry::add(std::string style, PairStyleFactory factory,
                            std::vector<config::Param> params, std::string doc) {
  auto& table = factories();
  if (table.count(style) != 0) throw Error("pair style '" + style + "' is already registered");
  table.emplace(std::move(style), Entry{std::move(factory), std::move(params), std::move(doc)});
}

}  // namespace pbms::dpd
