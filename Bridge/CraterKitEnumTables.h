// The proxies' enumerated properties and the solver choices they stand for: one named table
// per <EnumerationDomain> of Plugin/xml/*.xml, one row {value, text, solver} per
// <Entry value="..." text="...">. A filter turns such a property into a solver setting only
// through its table, so that the XML and the solvers meet in one place;
// tests/unit/EnumTablesTest.cpp checks every XML entry against these rows both ways.
//
// Plain C++ (no VTK): the unit tests include it without ParaView.
#pragma once

#include "bed/GranularBed.h"
#include "bed/SizeDistribution.h"
#include "bonded/BondedBody.h"
#include "bonded/ShockViscosity.h"
#include "common/Container.h"
#include "common/Error.h"
#include "dem/DemSolver.h"
#include "edmd/HardDiskCrater.h"
#include "sph/ImpactSetup.h"
#include "sph/SphSolver.h"

#include <array>
#include <cstddef>
#include <string>
#include <string_view>

namespace craterkit::enums {

template <class E> struct Row {
  int value;             // the XML entry's value
  std::string_view text; // the XML entry's text
  E solver;              // what the solvers take for it
};

template <class E, std::size_t N> struct Table {
  std::string_view proxy, property; // where the XML declares the enumeration
  std::array<Row<E>, N> rows;

  const Row<E>& row(int value) const {
    for (const Row<E>& r : rows)
      if (r.value == value)
        return r;
    throw InputError(std::string(proxy) + "." + std::string(property) + ": no choice " +
                     std::to_string(value));
  }
  E toSolver(int value) const { return row(value).solver; }
  std::string_view text(int value) const { return row(value).text; }
  int toValue(const E& solver) const {
    for (const Row<E>& r : rows)
      if (r.solver == solver)
        return r.value;
    throw InputError(std::string(proxy) + "." + std::string(property) + ": no such choice");
  }
};

// DEMIntegrator.
inline const Table<std::string_view, 2> kContactLaw{
    "DEMIntegrator",
    "ContactLaw",
    {{{0, "LinearSpringDashpot", "LinearSpringDashpot"}, {1, "Hertz", "Hertz"}}}};

// Where the DEM's walls come from: the input bed's container (its field data), none, or one
// of these shapes.
enum class DemContainer { FromInput, None, Box, Bowl, Cylinder };
inline const Table<DemContainer, 5> kDemContainer{"DEMIntegrator",
                                                  "Container",
                                                  {{{0, "FromInput", DemContainer::FromInput},
                                                    {1, "None", DemContainer::None},
                                                    {2, "Box", DemContainer::Box},
                                                    {3, "Bowl", DemContainer::Bowl},
                                                    {4, "Cylinder", DemContainer::Cylinder}}}};

inline const Table<Gravity::Type, 3> kGravityModel{"DEMIntegrator",
                                                   "GravityModel",
                                                   {{{0, "None", Gravity::Type::None},
                                                     {1, "Uniform", Gravity::Type::Uniform},
                                                     {2, "PointMass", Gravity::Type::PointMass}}}};

// GranularBed.
inline const Table<GranularBedParams::Packing, 3> kPacking{
    "GranularBed",
    "Packing",
    {{{0, "RCP", GranularBedParams::Packing::RCP},
      {1, "HCP", GranularBedParams::Packing::HCP},
      {2, "Loose", GranularBedParams::Packing::Loose}}}};

inline const Table<Container::Type, 2> kBedContainer{
    "GranularBed",
    "Container",
    {{{0, "Box", Container::Type::Box}, {1, "Bowl", Container::Type::Bowl}}}};

inline const Table<SizeDistribution::Type, 3> kSizeDistribution{
    "GranularBed",
    "SizeDistribution",
    {{{0, "Monodisperse", SizeDistribution::Type::Monodisperse},
      {1, "Uniform", SizeDistribution::Type::Uniform},
      {2, "PowerLaw", SizeDistribution::Type::PowerLaw}}}};

// HardDiskCrater: the presets by their names in HardDiskCraterParams::preset ("" for Custom,
// the properties as set).
inline const Table<std::string_view, 4> kHardDiskPreset{
    "HardDiskCrater",
    "Preset",
    {{{0, "Custom", ""},
      {1, "Ball pit", "Ball pit"},
      {2, "Dense sand", "Dense sand"},
      {3, "Clump impactor", "Clump impactor"}}}};

inline const Table<HardDiskCraterParams::Impactor, 2> kImpactorType{
    "HardDiskCrater",
    "ImpactorType",
    {{{0, "Disk", HardDiskCraterParams::Impactor::Disk},
      {1, "Clump", HardDiskCraterParams::Impactor::Clump}}}};

// ImpactHandoff: what becomes of the ejecta (HandoffParams::groupEjecta, dropEjecta).
struct EjectaHandling {
  bool group, drop;
  bool operator==(const EjectaHandling& o) const { return group == o.group && drop == o.drop; }
};
inline const Table<EjectaHandling, 3> kEjectaParticles{"ImpactHandoff",
                                                       "EjectaParticles",
                                                       {{{0, "OnePerSPHParticle", {false, false}},
                                                         {1, "GroupedToBedSize", {true, false}},
                                                         {2, "Dropped", {true, true}}}}};

// SPHImpact.
inline const Table<SphImpactSetup::Shape, 2> kTargetShape{
    "SPHImpact",
    "TargetShape",
    {{{0, "HalfSpace", SphImpactSetup::Shape::HalfSpace},
      {1, "Hemisphere", SphImpactSetup::Shape::Hemisphere}}}};

inline const Table<SphParams::Kernel, 2> kKernel{
    "SPHImpact",
    "Kernel",
    {{{0, "CubicSpline", SphParams::Kernel::CubicSpline},
      {1, "WendlandC2", SphParams::Kernel::WendlandC2}}}};

// BondedImpact.
inline const Table<ProjectileShape, 2> kProjectileShape{
    "BondedImpact",
    "ProjectileShape",
    {{{0, "Sphere", ProjectileShape::Sphere}, {1, "Cylinder", ProjectileShape::Cylinder}}}};

// The dissipative term by the name of its class (bonded/ShockViscosity.h); 0 is the paper's model.
inline const Table<BondedDissipation, 2> kDissipation{
    "BondedImpact",
    "Dissipation",
    {{{0, "None", BondedDissipation::None},
      {1, "ShockViscosity", BondedDissipation::ShockViscosity}}}};

// LAMMPSDeckWriter: DEMIntegrator's DEM choices under the writer's name (the same rows, so that
// a deck is set up as the integrator would run).
inline const Table<std::string_view, 2> kDeckContactLaw{"LAMMPSDeckWriter", "ContactLaw",
                                                        kContactLaw.rows};
inline const Table<DemContainer, 5> kDeckContainer{"LAMMPSDeckWriter", "Container",
                                                   kDemContainer.rows};
inline const Table<Gravity::Type, 3> kDeckGravityModel{"LAMMPSDeckWriter", "GravityModel",
                                                       kGravityModel.rows};

// Every table above, for the checks that go through all of them.
template <class F> void forEachTable(F&& f) {
  f(kContactLaw);
  f(kDemContainer);
  f(kGravityModel);
  f(kPacking);
  f(kBedContainer);
  f(kSizeDistribution);
  f(kHardDiskPreset);
  f(kImpactorType);
  f(kEjectaParticles);
  f(kTargetShape);
  f(kKernel);
  f(kProjectileShape);
  f(kDissipation);
  f(kDeckContactLaw);
  f(kDeckContainer);
  f(kDeckGravityModel);
}

} // namespace craterkit::enums
