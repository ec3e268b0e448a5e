// What a hand-off reports beside its particles (Handoff.h): the ratio of mapped to compact
// mass and the named figures ImpactHandoff writes as field data.
#include "handoff/Handoff.h"

namespace craterkit {

double compactMassRatio(const HandoffResult& r) {
  const double below = r.sphCompact.mass - r.sphCurtain.mass; // the compact mass the bed takes
  return below > 0.0 ? r.demMapped.mass / below : 0.0;
}

std::vector<NamedValue> reportedFigures(const HandoffResult& r) {
  std::vector<NamedValue> f;
  auto totals = [&](const std::string& prefix, const HandoffTotals& t) {
    f.push_back(NamedValue::number(prefix + "Mass", t.mass));
    const auto& p = t.momentum;
    const auto& l = t.angularMomentum;
    f.push_back(NamedValue::vector(prefix + "Momentum", std::vector<double>(p.begin(), p.end())));
    f.push_back(
        NamedValue::vector(prefix + "AngularMomentum", std::vector<double>(l.begin(), l.end())));
  };
  auto count = [&](const char* name, double value) {
    f.push_back(NamedValue::number(name, value));
  };
  totals("SPHCompact", r.sphCompact);
  totals("SPHEjecta", r.sphEjecta);
  totals("SPHCurtain", r.sphCurtain);
  totals("SPHEscaped", r.sphEscaped);
  count("EscapedCount", static_cast<double>(r.escapedCount));
  totals("SPHLoneDropped", r.sphLoneDropped);
  count("LoneDroppedCount", static_cast<double>(r.loneDropped));
  totals("DEMMappedBeforeCorrection", r.demBefore);
  totals("DEMMapped", r.demMapped);
  totals("DEMEjecta", r.demEjecta);
  count("CompactMassRatio", compactMassRatio(r));
  count("CurtainCount", static_cast<double>(r.curtainCount));
  count("AlphaRadius", r.alphaRadius);
  count("AlphaShapeVolume", r.shapeVolume);
  count("BedRemoved", static_cast<double>(r.bedRemoved));
  count("BedMapped", static_cast<double>(r.bedMapped));
  count("EjectaCount", static_cast<double>(r.ejectaCount));
  count("EjectaShrunk", static_cast<double>(r.ejectaShrunk));
  count("BedEvicted", static_cast<double>(r.bedEvicted));
  const HandoffResult::Timing& s = r.seconds;
  f.push_back(NamedValue::vector("StepSeconds",
                                 {s.split, s.alphaShape, s.carve, s.map, s.correct, s.ejecta}));
  return f;
}

} // namespace craterkit
