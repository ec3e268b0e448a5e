// The proxies' enumerations (every <EnumerationDomain> of Plugin/xml/*.xml) against the named
// tables the filters map them through (Bridge/CraterKitEnumTables.h): every XML entry has its
// row, value -> solver -> value round-trips, the texts agree, and no table has a row the XML
// lacks.
#include "CraterKitEnumTables.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

using namespace craterkit;

namespace {

struct XmlEnum {
  std::string proxy, property;
  std::vector<std::pair<int, std::string>> entries;
};

std::vector<XmlEnum> readXmlEnums() {
  std::vector<XmlEnum> out;
  const std::filesystem::path dir = std::filesystem::path(CRATERKIT_SOURCE_DIR) / "Plugin" / "xml";
  const std::regex proxy(R"re(<(\w*Proxy)\s+name="([^"]+)")re");
  const std::regex property(R"re(<\w+Property\s+name="([^"]+)")re");
  const std::regex domain(R"re(<EnumerationDomain[^>]*>([\s\S]*?)</EnumerationDomain>)re");
  const std::regex entry(R"re(<Entry\s+value="(-?\d+)"\s+text="([^"]*)")re");
  for (const auto& file : std::filesystem::directory_iterator(dir)) {
    if (file.path().extension() != ".xml")
      continue;
    std::ifstream in(file.path());
    std::stringstream buffer;
    buffer << in.rdbuf();
    const std::string text = buffer.str();
    for (auto d = std::sregex_iterator(text.begin(), text.end(), domain);
         d != std::sregex_iterator(); ++d) {
      // The enclosing proxy and property: the last ones declared before the domain.
      const std::string before = text.substr(0, static_cast<std::size_t>(d->position()));
      XmlEnum e;
      for (auto m = std::sregex_iterator(before.begin(), before.end(), proxy);
           m != std::sregex_iterator(); ++m)
        e.proxy = (*m)[2];
      for (auto m = std::sregex_iterator(before.begin(), before.end(), property);
           m != std::sregex_iterator(); ++m)
        e.property = (*m)[1];
      const std::string body = (*d)[1];
      for (auto m = std::sregex_iterator(body.begin(), body.end(), entry);
           m != std::sregex_iterator(); ++m)
        e.entries.emplace_back(std::stoi((*m)[1]), (*m)[2]);
      out.push_back(e);
    }
  }
  return out;
}

} // namespace

TEST(EnumTables, EveryXmlEntryRoundTripsThroughItsTable) {
  const std::vector<XmlEnum> xml = readXmlEnums();
  ASSERT_GE(xml.size(), 11u);
  std::map<std::pair<std::string, std::string>, int> tablesFound;
  for (const XmlEnum& e : xml) {
    SCOPED_TRACE(e.proxy + "." + e.property);
    ASSERT_FALSE(e.entries.empty());
    int matches = 0;
    enums::forEachTable([&](const auto& table) {
      if (table.proxy != e.proxy || table.property != e.property)
        return;
      ++matches;
      EXPECT_EQ(table.rows.size(), e.entries.size()) << "a table row the XML does not have";
      for (const auto& [value, text] : e.entries) {
        SCOPED_TRACE(text);
        EXPECT_EQ(table.text(value), text);
        EXPECT_EQ(table.toValue(table.toSolver(value)), value);
      }
    });
    EXPECT_EQ(matches, 1) << "no table (or more than one) for this enumeration";
    ++tablesFound[{e.proxy, e.property}];
  }
  // And no table without its enumeration in the XML.
  enums::forEachTable([&](const auto& table) {
    const std::pair<std::string, std::string> key{table.proxy, table.property};
    EXPECT_EQ(tablesFound[key], 1) << table.proxy << "." << table.property;
  });
}

TEST(EnumTables, UnknownValuesAreInputErrors) {
  EXPECT_THROW(enums::kKernel.toSolver(7), InputError);
  EXPECT_THROW(enums::kPacking.toSolver(-1), InputError);
}

TEST(EnumTables, HardDiskPresetsAreTheSolversPresets) {
  std::vector<std::string> names;
  for (const auto& row : enums::kHardDiskPreset.rows)
    if (!row.solver.empty())
      names.emplace_back(row.solver);
  EXPECT_EQ(names, HardDiskCraterParams::presetNames());
  EXPECT_TRUE(enums::kHardDiskPreset.toSolver(0).empty()); // Custom: the properties as set
}
