#include "io/DumpColumns.h"

#include <map>
#include <tuple>

namespace craterkit {
namespace dump {

Col columnKind(std::string_view name) {
  static const std::map<std::string_view, Col> known = {{"id", Col::Id},
                                                        {"type", Col::Type},
                                                        {"x", Col::X},
                                                        {"y", Col::Y},
                                                        {"z", Col::Z},
                                                        {"xu", Col::X},
                                                        {"yu", Col::Y},
                                                        {"zu", Col::Z},
                                                        {"xs", Col::Xs},
                                                        {"ys", Col::Ys},
                                                        {"zs", Col::Zs},
                                                        {"vx", Col::Vx},
                                                        {"vy", Col::Vy},
                                                        {"vz", Col::Vz},
                                                        {"omegax", Col::Wx},
                                                        {"omegay", Col::Wy},
                                                        {"omegaz", Col::Wz},
                                                        {"radius", Col::Radius},
                                                        {"diameter", Col::Diameter},
                                                        {"mass", Col::Mass},
                                                        {"density", Col::Density}};
  const auto it = known.find(name);
  return it == known.end() ? Col::Extra : it->second;
}

DumpColumns classifyColumns(std::vector<std::string> names, ParticleFrame& f, const Cursor& c,
                            std::size_t headerLine) {
  DumpColumns cols;
  cols.names = std::move(names);
  const std::vector<std::string>& n = cols.names;
  const std::size_t ncol = n.size();
  std::vector<Col>& kind = cols.kind;
  bool* const has = cols.has;
  kind.resize(ncol);
  for (std::size_t k = 0; k < ncol; ++k) {
    kind[k] = columnKind(n[k]);
    if (kind[k] != Col::Extra && has[static_cast<int>(kind[k])])
      c.fail("column '" + n[k] + "' appears twice", headerLine);
    has[static_cast<int>(kind[k])] = true;
  }
  const bool scaled = has[static_cast<int>(Col::Xs)] || has[static_cast<int>(Col::Ys)] ||
                      has[static_cast<int>(Col::Zs)];
  for (const auto& [a, b, name] :
       {std::tuple{Col::X, Col::Xs, "x"}, std::tuple{Col::Y, Col::Ys, "y"},
        std::tuple{Col::Z, Col::Zs, "z"}})
    if (!has[static_cast<int>(a)] && !has[static_cast<int>(b)])
      c.fail(std::string("the ATOMS line has no '") + name + "' column (x, xu or xs)", headerLine);
  if (scaled && !f.hasBox)
    c.fail("scaled coordinates without BOX BOUNDS", headerLine);

  std::vector<int>& extraIndex = cols.extraIndex;
  std::vector<int>& extraComp = cols.extraComp;
  extraIndex.assign(ncol, -1);
  extraComp.assign(ncol, 0);
  for (std::size_t k = 0; k < ncol; ++k) {
    if (kind[k] != Col::Extra || extraIndex[k] >= 0)
      continue;
    const std::string& a = n[k];
    if (k + 2 < ncol && kind[k + 1] == Col::Extra && kind[k + 2] == Col::Extra && a.size() > 1 &&
        a.back() == 'x' && n[k + 1] == a.substr(0, a.size() - 1) + "y" &&
        n[k + 2] == a.substr(0, a.size() - 1) + "z") {
      f.extra.push_back(ExtraArray{a.substr(0, a.size() - 1), 3, {}});
      for (int j = 0; j < 3; ++j) {
        extraIndex[k + j] = static_cast<int>(f.extra.size() - 1);
        extraComp[k + j] = j;
      }
    } else {
      f.extra.push_back(ExtraArray{a, 1, {}});
      extraIndex[k] = static_cast<int>(f.extra.size() - 1);
    }
  }
  return cols;
}

} // namespace dump
} // namespace craterkit
