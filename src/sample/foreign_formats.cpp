// LAMMPS data files and ESyS-Particle LSMGeometry files (declared in sample/formats.hpp).
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <limits>

#include "core/units.hpp"
#include "rupture/version.hpp"
#include "sample/formats.hpp"
#include "sample/generator.hpp"
#include "sample/text_reader.hpp"

namespace rupture {

using sample_detail::SampleAssembler;
using sample_detail::TextReader;

namespace {
// The title line marks files rupture wrote, whose atom types are its glued groups.
constexpr std::string_view lammps_title = "LAMMPS data file: rupture sample";

bool starts_with_letter(std::string_view line) {
  return !line.empty() && ((line[0] >= 'A' && line[0] <= 'Z') || (line[0] >= 'a' && line[0] <= 'z'));
}

// Column positions of one LAMMPS atom style.
struct AtomLayout {
  int id = 0, type = 1, x = 2, diameter = -1, density = -1, molecule = -1;  // -1: no such column
  std::size_t columns = 0;
};

AtomLayout atom_layout(const TextReader& in, const std::vector<std::string_view>& style) {
  const std::string supported =
      "supported: 'hybrid sphere bond', 'hybrid bond sphere', 'bpm/sphere', 'sphere'";
  if (style.empty())
    in.fail("the Atoms section does not name its atom style",
            "write it as a comment: 'Atoms # hybrid sphere bond'");
  // LAMMPS's own write_data names a hybrid style without its sub-styles ("Atoms # hybrid"); take
  // the order rupture writes, `sphere bond`, which the column count and types then check.
  if (style.size() == 1 && style[0] == "hybrid") return atom_layout(in, {"hybrid", "sphere", "bond"});
  AtomLayout layout;
  if (style[0] == "bpm/sphere") return {0, 2, 5, 3, 4, 1, 8};
  if (style[0] == "sphere") return {0, 1, 4, 2, 3, -1, 7};
  if (style[0] != "hybrid")
    in.fail(fmt::format("atom style '{}' has no particle radius", excerpt(style[0])), supported);
  int column = 5;  // id type x y z, then each sub-style's own columns in order
  for (std::size_t k = 1; k < style.size(); ++k) {
    const auto sub = style[k];
    if (sub == "sphere") {
      layout.diameter = column;
      layout.density = column + 1;
      column += 2;
    } else if (sub == "bond" || sub == "angle" || sub == "molecular") {
      layout.molecule = column;
      column += 1;
    } else if (sub == "charge") {
      column += 1;  // q
    } else if (sub == "full") {
      layout.molecule = column;
      column += 2;  // molecule-ID q
    } else {
      in.fail(fmt::format("hybrid sub-style '{}' is not supported", excerpt(sub)), supported);
    }
  }
  if (layout.diameter < 0) in.fail("the hybrid atom style has no 'sphere' part, so no radius", supported);
  layout.columns = static_cast<std::size_t>(column);
  return layout;
}

// GenGeo writes the bounding box of its neighbour table, which is rounded up to whole grid cells, not
// the box it packed against. A face that no particle comes within one smallest radius of is therefore
// not a wall of the packing: it is moved to the particles' extent. Faces the packing touches (every
// face of a generated sample) stay exactly as written. Returns whether a face moved.
bool fit_box_to_particles(Sample& sample) {
  if (sample.size() == 0) return false;
  const double r_min = default_glue_depth(sample);
  std::array<double, 3> low{}, high{};
  for (int a = 0; a < 3; ++a)
    low[a] = std::numeric_limits<double>::max(), high[a] = std::numeric_limits<double>::lowest();
  for (std::size_t k = 0; k < sample.size(); ++k) {
    const Vec3& p = sample.position[k];
    const std::array<double, 3> c{p.x, p.y, p.z};
    for (int a = 0; a < 3; ++a) {
      low[a] = std::min(low[a], c[a] - sample.radius[k]);
      high[a] = std::max(high[a], c[a] + sample.radius[k]);
    }
  }
  bool moved = false;
  const auto fit = [&](double& lower, double& upper, int a) {
    if (low[a] - lower > r_min) lower = low[a], moved = true;
    if (upper - high[a] > r_min) upper = high[a], moved = true;
  };
  fit(sample.box.lower.x, sample.box.upper.x, 0);
  fit(sample.box.lower.y, sample.box.upper.y, 1);
  fit(sample.box.lower.z, sample.box.upper.z, 2);
  return moved;
}
}  // namespace

// ---------------------------------------------------------------------------------------------
// LAMMPS

std::string format_lammps_data(const Sample& sample, LammpsAtomStyle style) {
  fmt::memory_buffer out;
  auto it = std::back_inserter(out);
  fmt::format_to(
      it,
      "{} written by rupture {}; lengths mm, density g/mm^3, atom-ID = rupture id + 1, atom types 1 "
      "free 2 bottom 3 top\n\n",
      lammps_title, version_string);
  fmt::format_to(it, "{} atoms\n3 atom types\n{} bonds\n1 bond types\n\n", sample.size(),
                 sample.bonds.size());
  const Box& b = sample.box;
  fmt::format_to(it, "{} {} xlo xhi\n{} {} ylo yhi\n{} {} zlo zhi\n\n", b.lower.x, b.upper.x, b.lower.y,
                 b.upper.y, b.lower.z, b.upper.z);
  const bool bpm = style == LammpsAtomStyle::bpm_sphere;
  fmt::format_to(it, "Atoms # {}\n\n", bpm ? "bpm/sphere" : "hybrid sphere bond");
  for (const auto k : sample_detail::id_order(sample)) {
    // atom-ID = id + 1 must lie in 1 .. 2^63 - 1 (checked before adding, which could overflow).
    if (sample.id[k] < 0 || sample.id[k] == std::numeric_limits<std::int64_t>::max())
      throw InputError("LAMMPS export",
                       fmt::format("particle id {} has no LAMMPS atom-ID (id + 1)", sample.id[k]),
                       "renumber the sample's ids from 0 (e.g. through the own format) first");
    const std::int64_t atom_id = sample.id[k] + 1;
    const int type = 1 + static_cast<int>(sample.group[k]);
    const Vec3& p = sample.position[k];
    const double diameter = 2.0 * sample.radius[k];
    if (bpm)
      fmt::format_to(it, "{} 1 {} {} {} {} {} {}\n", atom_id, type, diameter, sample.density, p.x, p.y, p.z);
    else
      fmt::format_to(it, "{} {} {} {} {} {} {} 1\n", atom_id, type, p.x, p.y, p.z, diameter, sample.density);
  }
  if (!sample.bonds.empty()) {
    fmt::format_to(it, "\nBonds\n\n");
    std::size_t bond_id = 1;
    for (const auto& bond : sample_detail::bonds_by_id(sample))
      fmt::format_to(it, "{} 1 {} {}\n", bond_id++, bond.a + 1, bond.b + 1);
  }
  return fmt::to_string(out);
}

namespace {

// The header of a LAMMPS data file: counts and box, up to the first section's header line.
struct LammpsHeader {
  std::size_t atoms = 0, bonds = 0;
  Box box;
  std::string_view first_section;  // empty: no section at all
};

LammpsHeader read_lammps_header(TextReader& in) {
  LammpsHeader h;
  bool have_atoms = false;
  std::array<bool, 3> have_bounds{};
  std::string_view line;
  while (in.next(line)) {
    if (starts_with_letter(line)) {
      h.first_section = line;
      break;
    }
    const auto words = tokens::words(line);
    if (words.size() == 2 && words[1] == "atoms") {
      h.atoms = in.count(words[0], "atom count");
      have_atoms = true;
    } else if (words.size() == 2 && words[1] == "bonds") {
      h.bonds = in.count(words[0], "bond count");
    } else if (words.size() == 4 && words[2].size() == 3 && words[2].substr(1) == "lo" &&
               words[3].substr(1) == "hi") {
      const int axis = words[2][0] - 'x';
      if (axis < 0 || axis > 2) in.fail(fmt::format("unknown bounds keyword '{}'", excerpt(words[2])));
      const double lo = in.real(words[0], "lower bound"), hi = in.real(words[1], "upper bound");
      if (!(hi > lo)) in.fail(fmt::format("{} bounds {} {} are empty", words[2], lo, hi));
      (axis == 0 ? h.box.lower.x : axis == 1 ? h.box.lower.y : h.box.lower.z) = lo;
      (axis == 0 ? h.box.upper.x : axis == 1 ? h.box.upper.y : h.box.upper.z) = hi;
      have_bounds[static_cast<std::size_t>(axis)] = true;
    } else if (words.size() >= 4 && words[3] == "yz") {
      in.fail("triclinic boxes are not supported", "write the data file from an orthogonal box");
    }
    // Other header lines (angles, type counts, extra per-atom counts, ...) do not concern a sample.
  }
  if (!have_atoms) in.fail("no 'N atoms' line in the header: this is not a LAMMPS data file");
  if (!(have_bounds[0] && have_bounds[1] && have_bounds[2]))
    in.fail("the header lacks one of the 'xlo xhi', 'ylo yhi', 'zlo zhi' lines");
  return h;
}

// A section's data lines (split into words) up to the next header line starting with a letter,
// which it returns (an empty view at the end of the file).
template <class Use>
std::string_view for_each_data_line(TextReader& in, Use&& use) {
  std::string_view data;
  while (in.next(data)) {
    if (starts_with_letter(data)) return data;
    use(tokens::words(data));
  }
  return {};
}

// LAMMPS atom-IDs are positive; the sample's id is the atom-ID - 1.
std::int64_t sample_id(const TextReader& in, std::string_view word, std::string_view what) {
  const std::int64_t atom_id = in.integer(word, what);
  if (atom_id < 1) in.fail(fmt::format("{} {} is not positive", what, atom_id), "LAMMPS atom-IDs start at 1");
  return atom_id - 1;
}

// What the Atoms section adds up to: the sample's one density is the atoms' common one, or their
// mass-weighted mean (g/mm^3).
struct AtomTotals {
  double mass = 0.0, volume = 0.0, common_density = -1.0;
  bool one_density = true;
  std::size_t read = 0;
};

// The Atoms section, its layout from the style comment on its header line; returns the next header.
std::string_view read_atoms(TextReader& in, bool written_by_rupture, SampleAssembler& build,
                            AtomTotals& totals) {
  const std::string_view header = in.raw_line();
  const auto hash = header.find('#');
  const auto style_text = hash == std::string_view::npos ? std::string_view{} : header.substr(hash + 1);
  const AtomLayout layout = atom_layout(in, tokens::words(style_text));
  return for_each_data_line(in, [&](const std::vector<std::string_view>& words) {
    if (words.size() != layout.columns && words.size() != layout.columns + 3)
      in.fail(fmt::format("{} columns where atom style '{}' has {} (or {} with image flags)", words.size(),
                          tokens::trim(style_text), layout.columns, layout.columns + 3));
    const auto column = [&](int k) { return words[static_cast<std::size_t>(k)]; };
    const auto id = sample_id(in, column(layout.id), "atom-ID");
    const double diameter = in.real(column(layout.diameter), "diameter");
    if (!(diameter > 0.0))
      in.fail(fmt::format("atom {} has diameter {}", id + 1, diameter), "give every atom a diameter > 0");
    const double density = in.real(column(layout.density), "density");
    // An integer molecule-ID where the layout expects one confirms the column order.
    if (layout.molecule >= 0) in.integer(column(layout.molecule), "molecule-ID");
    const auto type = in.integer(column(layout.type), "atom-type");
    ParticleGroup group = ParticleGroup::free;
    if (written_by_rupture) {
      if (type < 1 || type > 3)
        in.fail(fmt::format("atom type {} is not 1, 2 or 3 (free, bottom, top)", type));
      group = static_cast<ParticleGroup>(type - 1);
    }
    const double radius = 0.5 * diameter;
    build.add_particle(in, id,
                       {in.real(column(layout.x), "x"), in.real(column(layout.x + 1), "y"),
                        in.real(column(layout.x + 2), "z")},
                       radius, group);
    totals.volume += units::sphere_volume(radius);
    totals.mass += density * units::sphere_volume(radius);
    if (totals.common_density < 0.0) totals.common_density = density;
    totals.one_density = totals.one_density && density == totals.common_density;
    ++totals.read;
  });
}

}  // namespace

Sample parse_lammps_data(std::string_view text, const std::string& source) {
  // The first line is a free title (it may contain '#'); the rest has '#' comments.
  const auto title = text.substr(0, text.find('\n'));
  const bool written_by_rupture = title.starts_with(lammps_title);
  TextReader in(text, source, '#', "see the LAMMPS data files rupture reads in docs/sample.md");
  std::string_view line;
  in.next(line);  // the title
  const LammpsHeader header = read_lammps_header(in);
  SampleAssembler build(1);
  build.sample.box = header.box;
  AtomTotals atoms;
  bool have_atoms_section = false;
  std::size_t bonds_read = 0;
  // Each section: a header line starting with a letter, then data lines up to the next header.
  for (std::string_view section = header.first_section; !section.empty();) {
    const auto name = tokens::words(section)[0];
    if (name == "Atoms") {
      have_atoms_section = true;
      section = read_atoms(in, written_by_rupture, build, atoms);
    } else if (name == "Bonds") {
      if (!have_atoms_section) in.fail("the Bonds section comes before Atoms", "put the Atoms section first");
      section = for_each_data_line(in, [&](const std::vector<std::string_view>& words) {
        in.expect_columns(words, 4, "bond-ID bond-type atom1 atom2");
        build.add_bond(in, sample_id(in, words[2], "atom1"), sample_id(in, words[3], "atom2"));
        ++bonds_read;
      });
    } else {
      section = for_each_data_line(in, [](const auto&) {});  // Masses, Velocities, coefficients, ...
    }
  }
  if (atoms.read != header.atoms)
    in.fail(fmt::format("the file has {} atom lines but its header says {} atoms", atoms.read, header.atoms),
            "the file is truncated or its header is wrong");
  if (bonds_read != header.bonds)
    in.fail(fmt::format("the file has {} bond lines but its header says {} bonds", bonds_read, header.bonds),
            "the file is truncated or its header is wrong");
  Sample sample = build.finish();
  if (!(atoms.mass > 0.0))
    in.fail("the atoms have no positive density", "give each atom its density in g/mm^3");
  sample.density = atoms.one_density ? atoms.common_density : atoms.mass / atoms.volume;
  sample.provenance.push_back(fmt::format("imported from LAMMPS data file {}", source));
  if (!written_by_rupture) {
    // Another workflow's box is often larger than the packing (a margin, a shrink-wrapped boundary):
    // the glued layers are those within one smallest radius of the particles' own extent.
    if (fit_box_to_particles(sample))
      sample.provenance.push_back(
          "box fitted to the particles' extent (the file's box lies more than one smallest "
          "radius outside them)");
    assign_glued_layers(sample);
    sample.provenance.push_back(
        "glued layers: particles within one smallest radius of the bottom and top faces");
  }
  return sample;
}

// ---------------------------------------------------------------------------------------------
// LSMGeometry 1.2

std::string format_lsm_geometry(const Sample& sample) {
  fmt::memory_buffer out;
  auto it = std::back_inserter(out);
  const Box& b = sample.box;
  fmt::format_to(it,
                 "LSMGeometry 1.2\nBoundingBox {} {} {} {} {} {}\nPeriodicBoundaries 0 0 0\nDimension 3D\n",
                 b.lower.x, b.lower.y, b.lower.z, b.upper.x, b.upper.y, b.upper.z);
  fmt::format_to(it, "BeginParticles\nSimple\n{}\n", sample.size());
  for (const auto k : sample_detail::id_order(sample)) {
    const Vec3& p = sample.position[k];
    fmt::format_to(it, "{} {} {} {} {} {}\n", p.x, p.y, p.z, sample.radius[k], sample.id[k],
                   static_cast<int>(sample.group[k]));
  }
  fmt::format_to(it, "EndParticles\nBeginConnect\n{}\n", sample.bonds.size());
  for (const auto& bond : sample_detail::bonds_by_id(sample)) fmt::format_to(it, "{} {} 0\n", bond.a, bond.b);
  fmt::format_to(it, "EndConnect\n");
  return fmt::to_string(out);
}

Sample parse_lsm_geometry(std::string_view text, const std::string& source) {
  TextReader in(text, source, 0, "see the LSMGeometry 1.2 layout in docs/sample.md");
  const auto keyword = [&](std::string_view what) {
    const auto line = in.require(fmt::format("'{}'", what));
    if (line != what) in.fail(fmt::format("expected '{}', found '{}'", what, excerpt(line)));
  };
  auto words = tokens::words(in.require("'LSMGeometry 1.2'"));
  if (words.size() != 2 || words[0] != "LSMGeometry") in.fail("not an LSMGeometry file");
  if (words[1] != "1.2" && words[1] != "1.1")
    in.fail(fmt::format("LSMGeometry version {} is not supported", words[1]),
            "write the file as version 1.2");
  SampleAssembler build;
  std::string_view line;
  for (;;) {
    line = in.require("'BeginParticles'");
    words = tokens::words(line);
    if (words[0] == "BeginParticles") break;
    if (words[0] == "BoundingBox") {
      in.expect_columns(words, 7, "BoundingBox xmin ymin zmin xmax ymax zmax");
      Box& box = build.sample.box;
      box.lower = {in.real(words[1], "xmin"), in.real(words[2], "ymin"), in.real(words[3], "zmin")};
      box.upper = {in.real(words[4], "xmax"), in.real(words[5], "ymax"), in.real(words[6], "zmax")};
    } else if (words[0] == "PeriodicBoundaries") {
      for (std::size_t k = 1; k < words.size(); ++k)
        if (words[k] != "0")
          in.fail("periodic boundaries are not supported", "generate the geometry without periodicity");
    } else if (words[0] == "Dimension" || words[0] == "Dimensions") {
      if (words.size() < 2 || words[1] != "3D")
        in.fail("only 3D geometries can be samples", "generate a 3D geometry");
    } else {
      in.fail(fmt::format("unknown header line '{}'", excerpt(line)));
    }
  }
  keyword("Simple");
  const auto particles = in.count(in.require("the particle count"), "particle count");
  for (std::size_t k = 0; k < particles; ++k) {
    words = tokens::words(in.require(fmt::format("particle {} of {}", k + 1, particles)));
    if (words.size() != 6)
      in.fail(fmt::format("{} columns where 6 were expected (x y z r id tag)", words.size()));
    build.add_particle(in, in.integer(words[4], "id"),
                       {in.real(words[0], "x"), in.real(words[1], "y"), in.real(words[2], "z")},
                       in.radius(words[3]));
  }
  keyword("EndParticles");
  if (in.next(line)) {
    if (line != "BeginConnect") in.fail(fmt::format("expected 'BeginConnect', found '{}'", excerpt(line)));
    const auto bonds = in.count(in.require("the connection count"), "connection count");
    for (std::size_t k = 0; k < bonds; ++k) {
      words = tokens::words(in.require(fmt::format("connection {} of {}", k + 1, bonds)));
      if (words.size() != 3)
        in.fail(fmt::format("{} columns where 3 were expected (id1 id2 tag)", words.size()));
      build.add_bond(in, in.integer(words[0], "id1"), in.integer(words[1], "id2"));
    }
    keyword("EndConnect");
  }
  const Box& box = build.sample.box;
  if (!(box.upper.x > box.lower.x && box.upper.y > box.lower.y && box.upper.z > box.lower.z))
    throw InputError(source, "no valid BoundingBox line", "add 'BoundingBox xmin ymin zmin xmax ymax zmax'");
  Sample sample = build.finish();
  sample.provenance.push_back(fmt::format("imported from LSMGeometry file {}", source));
  if (fit_box_to_particles(sample))
    sample.provenance.push_back(
        "box: BoundingBox faces that no particle comes near moved to the particles' extent");
  assign_glued_layers(sample);
  return sample;
}

}  // namespace rupture
