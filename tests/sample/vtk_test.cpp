#include "io/vtk.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "sample/formats.hpp"
#include "sample_fixture.hpp"
#include "support/tool.hpp"

namespace rupture {
namespace {

using ::testing::HasSubstr;

// A minimal XML reader, enough to check that a .vtp is well-formed and to read its arrays back:
// elements must nest properly, attributes are quoted, text between tags is kept per element.
struct XmlElement {
  std::string name;
  std::map<std::string, std::string> attributes;
  std::string text;
  std::vector<XmlElement> children;
  const XmlElement* child(const std::string& n) const {
    for (const auto& c : children)
      if (c.name == n) return &c;
    return nullptr;
  }
};

XmlElement parse_xml(const std::string& xml) {
  XmlElement root;
  std::vector<XmlElement*> open{&root};
  std::size_t k = 0;
  while (k < xml.size()) {
    if (xml[k] != '<') {
      const auto next = xml.find('<', k);
      open.back()->text += xml.substr(k, next - k);
      k = next == std::string::npos ? xml.size() : next;
      continue;
    }
    if (xml.compare(k, 4, "<!--") == 0) {
      const auto end = xml.find("-->", k);
      if (end == std::string::npos) throw std::runtime_error("unterminated comment");
      k = end + 3;
      continue;
    }
    const auto end = xml.find('>', k);
    if (end == std::string::npos) throw std::runtime_error("unterminated tag");
    std::string tag = xml.substr(k + 1, end - k - 1);
    k = end + 1;
    if (tag.front() == '?') continue;
    if (tag.front() == '/') {
      if (open.size() < 2 || open.back()->name != tag.substr(1))
        throw std::runtime_error("mismatched </" + tag.substr(1) + ">");
      open.pop_back();
      continue;
    }
    const bool self_closing = tag.back() == '/';
    if (self_closing) tag.pop_back();
    std::istringstream in(tag);
    XmlElement element;
    in >> element.name;
    std::string rest((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    for (std::size_t p = 0; (p = rest.find('=', p)) != std::string::npos;) {
      auto name_start = rest.find_last_of(" \t\n", p);
      const std::string name = rest.substr(name_start + 1, p - name_start - 1);
      if (rest[p + 1] != '"') throw std::runtime_error("unquoted attribute " + name);
      const auto close = rest.find('"', p + 2);
      element.attributes[name] = rest.substr(p + 2, close - p - 2);
      p = close + 1;
    }
    open.back()->children.push_back(std::move(element));
    if (!self_closing) open.push_back(&open.back()->children.back());
  }
  if (open.size() != 1) throw std::runtime_error("unclosed <" + open.back()->name + ">");
  return root;
}

std::vector<double> numbers(const XmlElement& e) {
  std::istringstream in(e.text);
  std::vector<double> v;
  for (double x; in >> x;) v.push_back(x);
  return v;
}

const XmlElement& array_named(const XmlElement& parent, const std::string& name) {
  for (const auto& c : parent.children)
    if (c.name == "DataArray" && c.attributes.at("Name") == name) return c;
  throw std::runtime_error("no DataArray " + name);
}

TEST(Vtp, SampleFileIsWellFormedAndReadsBackExactly) {
  const Sample& s = testing::small_tissue().sample;
  const testing::TempDir dir;
  save_sample(s, dir / "s.vtp");
  const XmlElement doc = parse_xml(testing::slurp(dir / "s.vtp"));
  const XmlElement* file = doc.child("VTKFile");
  ASSERT_NE(file, nullptr);
  EXPECT_EQ(file->attributes.at("type"), "PolyData");
  const XmlElement& piece = *file->child("PolyData")->child("Piece");
  ASSERT_EQ(std::stoul(piece.attributes.at("NumberOfPoints")), s.size());
  ASSERT_EQ(std::stoul(piece.attributes.at("NumberOfLines")), s.bonds.size());
  const auto points = numbers(array_named(*piece.child("Points"), "Points"));
  ASSERT_EQ(points.size(), 3 * s.size());
  for (std::size_t k = 0; k < s.size(); ++k) {  // generated samples: id order = storage order
    ASSERT_EQ(points[3 * k], s.position[k].x);
    ASSERT_EQ(points[3 * k + 2], s.position[k].z);
  }
  EXPECT_EQ(numbers(array_named(*piece.child("PointData"), "radius")), s.radius);
  const auto groups = numbers(array_named(*piece.child("PointData"), "group"));
  ASSERT_EQ(groups.size(), s.size());
  EXPECT_EQ(groups[0], static_cast<double>(s.group[0]));
  const auto connectivity = numbers(array_named(*piece.child("Lines"), "connectivity"));
  const auto offsets = numbers(array_named(*piece.child("Lines"), "offsets"));
  ASSERT_EQ(connectivity.size(), 2 * s.bonds.size());
  ASSERT_EQ(offsets.size(), s.bonds.size());
  EXPECT_EQ(offsets.back(), 2.0 * static_cast<double>(s.bonds.size()));
  EXPECT_EQ(connectivity[0], s.bonds[0].i);
  EXPECT_EQ(connectivity[1], s.bonds[0].j);
  const auto rest = numbers(array_named(*piece.child("CellData"), "rest_length"));
  ASSERT_EQ(rest.size(), s.bonds.size());
  EXPECT_EQ(rest.back(), s.bonds.back().rest_length);
}

TEST(Vtp, ArbitraryLineArraysAndEscapedNames) {
  io::VtkPolyData data;
  data.points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}};
  data.lines = {{0, 1}, {1, 2}};
  data.line_data.push_back({"extension <mm>", 1, std::vector<double>{0.25, -1e-3}});
  data.point_data.push_back({"velocity", 3, std::vector<double>(9, 0.5)});
  data.comments = {"made by a test -- with dashes"};
  const XmlElement doc = parse_xml(io::format_vtp(data));
  const XmlElement& piece = *doc.child("VTKFile")->child("PolyData")->child("Piece");
  EXPECT_EQ(numbers(array_named(*piece.child("CellData"), "extension &lt;mm&gt;")),
            (std::vector<double>{0.25, -1e-3}));
  EXPECT_EQ(array_named(*piece.child("PointData"), "velocity").attributes.at("NumberOfComponents"), "3");
}

TEST(Vtp, MismatchedArraysAreRejected) {
  io::VtkPolyData data;
  data.points = {{0, 0, 0}, {1, 0, 0}};
  data.lines = {{0, 1}};
  data.line_data.push_back({"extension", 1, std::vector<double>{1.0, 2.0}});
  EXPECT_THROW(io::format_vtp(data), std::invalid_argument);
  data.line_data.clear();
  data.lines = {{0, 2}};
  EXPECT_THROW(io::format_vtp(data), std::invalid_argument);
}

TEST(Pvd, CollectionListsEveryStep) {
  const XmlElement doc = parse_xml(io::format_pvd({{0.0, "snap_0.vtp"}, {1.5e-4, "snap_1.vtp"}}));
  const XmlElement& collection = *doc.child("VTKFile")->child("Collection");
  ASSERT_EQ(collection.children.size(), 2u);
  EXPECT_EQ(collection.children[1].attributes.at("file"), "snap_1.vtp");
  EXPECT_EQ(std::stod(collection.children[1].attributes.at("timestep")), 1.5e-4);
}

TEST(XmlChecker, RejectsMalformedDocuments) {  // the checker above can fail
  EXPECT_THROW(parse_xml("<a><b></a></b>"), std::runtime_error);
  EXPECT_THROW(parse_xml("<a x=1></a>"), std::runtime_error);
  EXPECT_THROW(parse_xml("<a>"), std::runtime_error);
}

}  // namespace
}  // namespace rupture
