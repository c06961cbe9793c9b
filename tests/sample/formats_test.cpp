#include "sample/formats.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "core/error.hpp"
#include "sample_fixture.hpp"
#include "support/tool.hpp"

namespace rupture {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;
using testing::small_tissue;
using ::testing::ThrowsMessage;

void expect_same_particles_and_bonds(const Sample& a, const Sample& b) {
  EXPECT_EQ(a.box.lower, b.box.lower);
  EXPECT_EQ(a.box.upper, b.box.upper);
  EXPECT_EQ(a.density, b.density);
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(a.id, b.id);
  EXPECT_EQ(a.position, b.position);  // exact: shortest round-trip decimals
  EXPECT_EQ(a.radius, b.radius);
  EXPECT_EQ(a.group, b.group);
  ASSERT_EQ(a.bonds.size(), b.bonds.size());
  for (std::size_t k = 0; k < a.bonds.size(); ++k) {
    ASSERT_EQ(a.bonds[k].i, b.bonds[k].i) << "bond " << k;
    ASSERT_EQ(a.bonds[k].j, b.bonds[k].j) << "bond " << k;
    ASSERT_EQ(a.bonds[k].rest_length, b.bonds[k].rest_length) << "bond " << k;
  }
}

TEST(OwnFormat, RoundTripIsIdentical) {
  const Sample& s = small_tissue().sample;
  const Sample back = parse_own(format_own(s), "mem");
  expect_same_particles_and_bonds(s, back);
  EXPECT_EQ(back.provenance, s.provenance);
  EXPECT_EQ(format_own(back), format_own(s));
}

TEST(LammpsData, RoundTripIsIdenticalInBothAtomStyles) {
  const Sample& s = small_tissue().sample;
  for (auto style : {LammpsAtomStyle::hybrid_sphere_bond, LammpsAtomStyle::bpm_sphere}) {
    const std::string text = format_lammps_data(s, style);
    expect_same_particles_and_bonds(s, parse_lammps_data(text, "mem.data"));
  }
}

TEST(LsmGeometry, RoundTripIsIdentical) {
  const Sample& s = small_tissue().sample;
  expect_same_particles_and_bonds(s, parse_lsm_geometry(format_lsm_geometry(s), "mem.geo"));
}

TEST(SampleFiles, SaveAndLoadChooseTheFormatByExtensionAndContent) {
  const testing::TempDir dir;
  const Sample& s = small_tissue().sample;
  for (const char* name : {"t.sample", "t.data", "t.geo"}) {
    save_sample(s, dir / name);
    expect_same_particles_and_bonds(s, load_sample(dir / name));
  }
  EXPECT_THAT(testing::slurp(dir / "t.geo"), ::testing::StartsWith("LSMGeometry 1.2\n"));
  EXPECT_THAT(testing::slurp(dir / "t.data"), HasSubstr("Atoms # hybrid sphere bond"));
  save_sample(s, dir / "t.vtp");
  EXPECT_THAT([&] { load_sample(dir / "t.vtp"); }, ThrowsMessage<InputError>(HasSubstr("not a sample")));
}

// A data file as LAMMPS itself writes it: other sections, image flags, sub-styles in the other order,
// atom ids from 1, a non-rupture title (so glued layers come from the glue rule).
TEST(LammpsData, ReadsAFileWrittenByLammps) {
  const std::string text =
      "LAMMPS data file via write_data, version 2 Aug 2023, timestep = 0, units = si\n\n"
      "3 atoms\n1 atom types\n2 bonds\n1 bond types\n\n"
      "0 4 xlo xhi\n0 4 ylo yhi\n0 2 zlo zhi\n\n"
      "Masses\n\n1 1.0\n\n"
      "Atoms # hybrid bond sphere\n\n"
      "1 1 1.0 0.5 1.0 7 1.0 0.002 0 0 0\n"
      "3 1 1.0 3.5 1.0 7 1.0 0.002 0 0 0\n"
      "2 1 1.0 2.0 1.0 7 1.0 0.002 0 0 0\n\n"
      "Velocities\n\n1 0 0 0\n2 0 0 0\n3 0 0 0\n\n"
      "Bonds\n\n1 1 1 2\n2 1 3 2\n";
  const Sample s = parse_lammps_data(text, "lmp.data");
  ASSERT_EQ(s.size(), 3u);
  EXPECT_EQ(s.id, (std::vector<std::int64_t>{0, 2, 1}));  // rupture id = atom-ID - 1, file order kept
  EXPECT_EQ(s.radius[1], 0.5);
  EXPECT_EQ(s.density, 0.002);
  EXPECT_EQ(s.group,
            (std::vector<ParticleGroup>{ParticleGroup::bottom, ParticleGroup::top, ParticleGroup::free}));
  ASSERT_EQ(s.bonds.size(), 2u);
  EXPECT_EQ(s.bonds[0].i, 0u);
  EXPECT_EQ(s.bonds[0].j, 2u);
  EXPECT_DOUBLE_EQ(s.bonds[0].rest_length, 1.5);
}

// Someone else's workflow leaves a margin around the packing (here 1 mm on every side): the glued
// layers are found against the particles' own extent, not 1 mm away where there are none.
TEST(LammpsData, GluedLayersOfAFileWhoseBoxHasAMargin) {
  const std::string text =
      "LAMMPS data file via write_data, version 2 Aug 2023, timestep = 0, units = si\n\n"
      "3 atoms\n1 atom types\n2 bonds\n1 bond types\n\n"
      "-1 5 xlo xhi\n-1 5 ylo yhi\n-1 3 zlo zhi\n\n"
      "Atoms # hybrid bond sphere\n\n"
      "1 1 1.0 0.5 1.0 7 1.0 0.002 0 0 0\n"
      "3 1 1.0 3.5 1.0 7 1.0 0.002 0 0 0\n"
      "2 1 1.0 2.0 1.0 7 1.0 0.002 0 0 0\n\n"
      "Bonds\n\n1 1 1 2\n2 1 3 2\n";
  const Sample s = parse_lammps_data(text, "margin.data");
  EXPECT_EQ(s.box.lower.y, 0.0);  // the particles' extent: 0.5 - 0.5 to 3.5 + 0.5
  EXPECT_EQ(s.box.upper.y, 4.0);
  EXPECT_EQ(s.group,
            (std::vector<ParticleGroup>{ParticleGroup::bottom, ParticleGroup::top, ParticleGroup::free}));
  EXPECT_THAT(s.provenance.back(), HasSubstr("glued layers"));
}

// LAMMPS's write_data names hybrid styles without their sub-styles; the order rupture writes is
// assumed and checked through the molecule-ID column.
TEST(LammpsData, BareHybridStyleIsReadAsSphereBond) {
  const std::string head =
      "LAMMPS data file via write_data\n\n1 atoms\n0 4 xlo xhi\n0 4 ylo yhi\n0 2 zlo zhi\n\n";
  const Sample s =
      parse_lammps_data(head + "Atoms # hybrid\n\n1 1 1.0 0.5 1.0 1.0 0.002 1 0 0 0\n", "h.data");
  ASSERT_EQ(s.size(), 1u);
  EXPECT_EQ(s.radius[0], 0.5);
  EXPECT_EQ(s.density, 0.002);
  EXPECT_THAT([&] { parse_lammps_data(head + "Atoms # hybrid\n\n1 1 1.0 0.5 1.0 7 1.0 0.002\n", "h.data"); },
              ThrowsMessage<InputError>(HasSubstr("h.data:10: molecule-ID '0.002' is not an integer")));
}

TEST(LsmGeometry, ReadsAGenGeoFile) {
  const std::string text =
      "LSMGeometry 1.2\nBoundingBox 0 0 0 4 4 2\nPeriodicBoundaries 0 0 0\nDimension 3D\n"
      "BeginParticles\nSimple\n2\n1 0.5 1 0.5 10 0\n1 1.5 1 0.5 11 1\nEndParticles\n"
      "BeginConnect\n1\n10 11 0\nEndConnect\n";
  const Sample s = parse_lsm_geometry(text, "g.geo");
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s.id, (std::vector<std::int64_t>{10, 11}));
  ASSERT_EQ(s.bonds.size(), 1u);
  EXPECT_DOUBLE_EQ(s.bonds[0].rest_length, 1.0);
  // GenGeo writes its grid's bounding box: faces no particle comes within r_min of move to the
  // particles' extent, so the top layer exists; faces the packing touches stay as written.
  EXPECT_EQ(s.box.upper.y, 2.0);
  EXPECT_EQ(s.box.upper.x, 1.5);
  EXPECT_EQ(s.box.upper.z, 2.0);  // a gap of exactly r_min still counts as a wall
  EXPECT_EQ(s.box.lower.x, 0.0);
  EXPECT_EQ(s.group[0], ParticleGroup::bottom);
  EXPECT_EQ(s.group[1], ParticleGroup::top);
}

TEST(OwnFormat, TruncatedFileIsRejectedNamingTheLine) {
  const std::string text = format_own(small_tissue().sample);
  const std::string cut = text.substr(0, text.size() / 3);  // ends inside the particles
  const auto cut_at_line = cut.substr(0, cut.rfind('\n') + 1);
  EXPECT_THAT([&] { parse_own(cut_at_line, "t.sample"); },
              ThrowsMessage<InputError>(
                  AllOf(HasSubstr("t.sample:"), HasSubstr("truncated"), HasSubstr("particle"))));
  // A line cut in the middle gives a short line.
  EXPECT_THAT([&] { parse_own(cut, "t.sample"); }, ThrowsMessage<InputError>(HasSubstr("t.sample:")));
  // Missing the last line.
  const auto no_end = text.substr(0, text.rfind("end\n"));
  EXPECT_THAT([&] { parse_own(no_end, "t.sample"); }, ThrowsMessage<InputError>(HasSubstr("truncated")));
}

TEST(OwnFormat, CorruptContentIsRejectedWithTheFix) {
  const std::string head = "rupture-sample 1\nbox 0 0 0 1 1 1\ndensity 0.00025\nparticles 2\n";
  const auto parse = [](const std::string& text) { parse_own(text, "c.sample"); };
  EXPECT_THAT([&] { parse("rupture-sample 2\n"); },
              ThrowsMessage<InputError>(HasSubstr("version 2 is not supported")));
  EXPECT_THAT([&] { parse("hello\n"); },
              ThrowsMessage<InputError>(HasSubstr("c.sample:1: not a rupture sample")));
  EXPECT_THAT(
      [&] { parse(head + "0 0.5 0.5 0.5 0.2 free\n1 0.5 0.5 0.5 0.2 middle\nbonds 0\nend\n"); },
      ThrowsMessage<InputError>(AllOf(HasSubstr("c.sample:6"), HasSubstr("use free, bottom or top"))));
  EXPECT_THAT([&] { parse(head + "0 0.5 0.5 0.5 0.2 free\n0 0.5 0.5 0.5 0.2 free\nbonds 0\nend\n"); },
              ThrowsMessage<InputError>(HasSubstr("id 0 appears twice")));
  EXPECT_THAT([&] { parse(head + "0 0.5 0.5 0.5 -0.2 free\n"); },
              ThrowsMessage<InputError>(HasSubstr("radius -0.2 mm is not positive")));
  EXPECT_THAT([&] { parse(head + "0 0.5 x 0.5 0.2 free\n"); },
              ThrowsMessage<InputError>(HasSubstr("y 'x' is not a finite number")));
  EXPECT_THAT([&] { parse(head + "0 0 0 0 0.2 free\n1 1 0 0 0.2 free\nbonds 1\n0 7 1\nend\n"); },
              ThrowsMessage<InputError>(HasSubstr("names particle id 7")));
  EXPECT_THAT([&] { parse(head + "0 0 0 0 0.2 free\n1 1 0 0 0.2 free\nbonds 1\n0 1 1\n0 1 1\nend\n"); },
              ThrowsMessage<InputError>(HasSubstr("expected 'end' after 1 bonds")));
}

TEST(LammpsData, TruncatedOrUnsupportedFilesAreRejected) {
  const std::string text = format_lammps_data(small_tissue().sample);
  const auto cut = text.substr(0, text.find("\n", text.size() / 2) + 1);
  EXPECT_THAT([&] { parse_lammps_data(cut, "t.data"); }, ThrowsMessage<InputError>(HasSubstr("truncated")));
  const std::string head = "title\n\n1 atoms\n0 1 xlo xhi\n0 1 ylo yhi\n0 1 zlo zhi\n\n";
  EXPECT_THAT(
      [&] { parse_lammps_data(head + "Atoms # bond\n\n1 1 1 0.5 0.5 0.5\n", "b.data"); },
      ThrowsMessage<InputError>(AllOf(HasSubstr("has no particle radius"), HasSubstr("hybrid sphere bond"))));
  EXPECT_THAT([&] { parse_lammps_data(head + "Atoms\n\n1 1 0.5 0.5 0.5 1 1\n", "b.data"); },
              ThrowsMessage<InputError>(HasSubstr("does not name its atom style")));
  EXPECT_THAT([&] { parse_lammps_data(head + "Atoms # sphere\n\n1 1 0.4 1 0.5 0.5\n", "b.data"); },
              ThrowsMessage<InputError>(HasSubstr("b.data:10: 6 columns")));
}

TEST(LsmGeometry, TruncatedOrUnsupportedFilesAreRejected) {
  const std::string text = format_lsm_geometry(small_tissue().sample);
  const auto cut = text.substr(0, text.find("\n", text.size() / 2) + 1);
  EXPECT_THAT([&] { parse_lsm_geometry(cut, "t.geo"); }, ThrowsMessage<InputError>(HasSubstr("truncated")));
  EXPECT_THAT(
      [&] { parse_lsm_geometry("LSMGeometry 1.2\nBoundingBox 0 0 0 1 1 1\nDimension 2D\n", "t.geo"); },
      ThrowsMessage<InputError>(HasSubstr("t.geo:3: only 3D")));
}

TEST(SampleFormat, NamesAndExtensions) {
  EXPECT_EQ(sample_format_for_path("a/b.DATA"), SampleFormat::lammps);
  EXPECT_EQ(sample_format_for_path("x.geo"), SampleFormat::lsm);
  EXPECT_EQ(sample_format_for_path("x.vtp"), SampleFormat::vtp);
  EXPECT_EQ(sample_format_for_path("x.sample"), SampleFormat::own);
  EXPECT_EQ(sample_format_from_name("lsm"), SampleFormat::lsm);
  EXPECT_THAT([] { sample_format_from_name("xyz"); },
              ThrowsMessage<InputError>(HasSubstr("own, lammps, lsm, vtp")));
}

}  // namespace
}  // namespace rupture
