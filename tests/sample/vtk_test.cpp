#include "io/vtk.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/error.hpp"
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

// The XML of a .vtp without its appended binary section, which is not text.
XmlElement parse_vtp_markup(const std::string& vtp) {
  const auto start = vtp.find("<AppendedData"), end = vtp.find("</AppendedData>");
  if (start == std::string::npos || end == std::string::npos) throw std::runtime_error("no appended data");
  return parse_xml(vtp.substr(0, start) + vtp.substr(end + std::string("</AppendedData>").size()));
}

const XmlElement& array_named(const XmlElement& parent, const std::string& name) {
  for (const auto& c : parent.children)
    if (c.name == "DataArray" && c.attributes.at("Name") == name) return c;
  throw std::runtime_error("no DataArray " + name);
}

std::vector<double> values_of(const io::VtkArray* array) {
  if (array == nullptr) throw std::runtime_error("no such array");
  return io::as_doubles(*array);
}

TEST(Vtp, SampleFileIsWellFormedBinaryAndReadsBackExactly) {
  const Sample& s = testing::small_tissue().sample;
  const testing::TempDir dir;
  save_sample(s, dir / "s.vtp");
  const std::string text = testing::slurp(dir / "s.vtp");
  const XmlElement doc = parse_vtp_markup(text);
  const XmlElement* file = doc.child("VTKFile");
  ASSERT_NE(file, nullptr);
  EXPECT_EQ(file->attributes.at("type"), "PolyData");
  EXPECT_EQ(file->attributes.at("compressor"), "vtkZLibDataCompressor");
  const XmlElement& piece = *file->child("PolyData")->child("Piece");
  ASSERT_EQ(std::stoul(piece.attributes.at("NumberOfPoints")), s.size());
  ASSERT_EQ(std::stoul(piece.attributes.at("NumberOfLines")), s.bonds.size());
  EXPECT_EQ(array_named(*piece.child("Points"), "Points").attributes.at("format"), "appended");
  EXPECT_EQ(array_named(*piece.child("PointData"), "radius").attributes.at("type"), "Float64");

  const io::VtkPolyData back = io::read_vtp(dir / "s.vtp");
  ASSERT_EQ(back.points.size(), s.size());
  for (std::size_t k = 0; k < s.size(); ++k) {  // generated samples: id order = storage order
    ASSERT_EQ(back.points[k].x, s.position[k].x);
    ASSERT_EQ(back.points[k].y, s.position[k].y);
    ASSERT_EQ(back.points[k].z, s.position[k].z);
  }
  EXPECT_EQ(values_of(back.point_array("radius")), s.radius);
  const auto groups = values_of(back.point_array("group"));
  ASSERT_EQ(groups.size(), s.size());
  EXPECT_EQ(groups[0], static_cast<double>(s.group[0]));
  ASSERT_EQ(back.lines.size(), s.bonds.size());
  for (std::size_t b = 0; b < s.bonds.size(); ++b) {
    ASSERT_EQ(back.lines[b][0], s.bonds[b].i);
    ASSERT_EQ(back.lines[b][1], s.bonds[b].j);
  }
  const auto rest = values_of(back.line_array("rest_length"));
  ASSERT_EQ(rest.size(), s.bonds.size());
  EXPECT_EQ(rest.back(), s.bonds.back().rest_length);
  // zlib: the binary file is smaller than the numbers written out as text would be.
  EXPECT_LT(text.size(), 24 * (4 * s.size() + s.bonds.size()));
}

TEST(Vtp, ArraysLargerThanOneZlibBlockAndEscapedNamesRoundTrip) {
  io::VtkPolyData data;
  const std::size_t n = 20000;  // 480 kB of Float64 points: several 64 kB blocks and a partial one
  for (std::size_t k = 0; k < n; ++k)
    data.points.push_back({0.5 * double(k), std::sqrt(double(k)), -1.0 / (1.0 + double(k))});
  for (std::uint32_t k = 0; k + 1 < n; ++k) data.lines.push_back({k, k + 1});
  std::vector<double> extension(n - 1);
  for (std::size_t k = 0; k + 1 < n; ++k) extension[k] = std::sin(double(k));
  data.line_data.push_back({"extension <mm>", 1, extension});
  data.point_data.push_back({"velocity", 3, std::vector<double>(3 * n, 0.5)});
  data.point_data.push_back({"id", 1, std::vector<std::int64_t>(n, -7)});
  data.comments = {"made by a test -- with dashes"};
  const std::string text = io::format_vtp(data);
  const XmlElement doc = parse_vtp_markup(text);
  const XmlElement& piece = *doc.child("VTKFile")->child("PolyData")->child("Piece");
  EXPECT_EQ(array_named(*piece.child("PointData"), "velocity").attributes.at("NumberOfComponents"), "3");
  array_named(*piece.child("CellData"), "extension &lt;mm&gt;");  // throws if the name is not escaped
  const io::VtkPolyData back = io::parse_vtp(text, "test");
  ASSERT_EQ(back.points.size(), n);
  EXPECT_EQ(back.points[n - 1].y, data.points[n - 1].y);
  EXPECT_EQ(back.lines, data.lines);
  EXPECT_EQ(values_of(back.line_array("extension <mm>")), extension);
  EXPECT_EQ(std::get<std::vector<std::int64_t>>(back.point_array("id")->values),
            std::vector<std::int64_t>(n, -7));
  EXPECT_EQ(back.point_array("velocity")->components, 3);
}

TEST(Vtp, OlderAsciiFilesAreStillRead) {
  const std::string ascii =
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\" "
      "header_type=\"UInt64\">\n<PolyData>\n<Piece NumberOfPoints=\"3\" NumberOfLines=\"2\">\n"
      "<Points>\n<DataArray type=\"Float64\" Name=\"Points\" NumberOfComponents=\"3\" format=\"ascii\">\n"
      "0 0 0\n1 0 0\n1 1 0.25\n</DataArray>\n</Points>\n<PointData>\n"
      "<DataArray type=\"Int64\" Name=\"group\" NumberOfComponents=\"1\" format=\"ascii\">\n1 0 "
      "2\n</DataArray>\n"
      "</PointData>\n<Lines>\n<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n0 1\n1 2\n"
      "</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n2 "
      "4\n</DataArray>\n</Lines>\n"
      "<CellData>\n<DataArray type=\"Float64\" Name=\"relative_extension\" NumberOfComponents=\"1\" "
      "format=\"ascii\">\n0.5 -1e-3\n</DataArray>\n</CellData>\n</Piece>\n</PolyData>\n</VTKFile>\n";
  const io::VtkPolyData back = io::parse_vtp(ascii, "old.vtp");
  ASSERT_EQ(back.points.size(), 3u);
  EXPECT_EQ(back.points[2].z, 0.25);
  EXPECT_EQ(back.lines, (std::vector<std::array<std::uint32_t, 2>>{{0, 1}, {1, 2}}));
  EXPECT_EQ(values_of(back.point_array("group")), (std::vector<double>{1, 0, 2}));
  EXPECT_EQ(values_of(back.line_array("relative_extension")), (std::vector<double>{0.5, -1e-3}));
}

TEST(Vtp, DamagedFilesAreRejectedNamingTheArray) {
  io::VtkPolyData data;
  data.points = {{0, 0, 0}, {1, 0, 0}};
  data.lines = {{0, 1}};
  data.line_data.push_back({"extension", 1, std::vector<double>{0.5}});
  const std::string text = io::format_vtp(data);
  const std::string cut = text.substr(0, text.size() - 40);  // the last array's bytes lost
  EXPECT_THAT([&] { io::parse_vtp(cut, "cut.vtp"); },
              ::testing::ThrowsMessage<InputError>(HasSubstr("cut.vtp: DataArray 'extension'")));
  const std::size_t appended =
      text.find("encoding=\"raw\">\n   _") + std::string("encoding=\"raw\">\n   _").size();
  std::string flipped = text;
  flipped[appended + 40] ^= 0x5a;  // inside the first compressed block (after its 4 x 8-byte header)
  EXPECT_THROW(io::parse_vtp(flipped, "flipped.vtp"), InputError);
  std::string huge = text;  // the first array's block count set to 2^64 - 1: refused, not allocated
  for (std::size_t k = 0; k < 8; ++k) huge[appended + k] = '\xff';
  EXPECT_THAT([&] { io::parse_vtp(huge, "huge.vtp"); },
              ::testing::ThrowsMessage<InputError>(HasSubstr("compression header is damaged")));
  EXPECT_THAT([&] { io::parse_vtp("<VTKFile byte_order=\"BigEndian\">", "big.vtp"); },
              ::testing::ThrowsMessage<InputError>(HasSubstr("BigEndian")));
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
