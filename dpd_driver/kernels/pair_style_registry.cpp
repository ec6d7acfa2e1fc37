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
std::map<std::string, PairStyleFactory, std::less<>>& factories() {
  static std::map<std::string, PairStyleFactory, std::less<>> table = {
      {std::string(Morse::kStyle), &Morse::create},
      {std::string(LjNm::kStyle), &LjNm::create},
      {std::string(PairTable::kStyle), &PairTable::create},
      {std::string(SuttonChen::kStyle), &SuttonChen::create},
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
  return it->second(params);
}

std::vector<std::string> PairStyleRegistry::names() {
  std::vector<std::string> out;
  for (const auto& [name, factory] : factories()) out.push_back(name);
  return out;
}

bool PairStyleRegistry::contains(std::string_view style) {
  return factories().find(style) != factories().end();
}

void PairStyleRegistry::add(std::string style, PairStyleFactory factory) {
  auto& table = factories();
  if (table.count(style) != 0) throw Error("pair style '" + style + "' is already registered");
  table.emplace(std::move(style), std::move(factory));
}

}  // namespace pbms::dpd
