#include "sample/formats.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>

#include "core/error.hpp"
#include "io/atomic_file.hpp"
#include "rupture/version.hpp"
#include "sample/text_reader.hpp"

namespace rupture {

using sample_detail::SampleAssembler;
using sample_detail::TextReader;

namespace fs = std::filesystem;

namespace {
constexpr std::array<std::string_view, 4> format_names{"own", "lammps", "lsm", "vtp"};
constexpr std::array<std::string_view, 3> group_names{"free", "bottom", "top"};
constexpr int own_format_version = 1;

std::string lower_extension(const fs::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}
}  // namespace

SampleFormat sample_format_from_name(std::string_view name) {
  for (std::size_t k = 0; k < format_names.size(); ++k)
    if (name == format_names[k]) return static_cast<SampleFormat>(k);
  throw InputError("--format", fmt::format("unknown sample format '{}'", name),
                   "use one of: own, lammps, lsm, vtp");
}

std::string_view sample_format_name(SampleFormat format) {
  return format_names[static_cast<std::size_t>(format)];
}

SampleFormat sample_format_for_path(const fs::path& path) {
  const auto ext = lower_extension(path);
  if (ext == ".geo" || ext == ".lsm") return SampleFormat::lsm;
  if (ext == ".data" || ext == ".lmp" || ext == ".lammps") return SampleFormat::lammps;
  if (ext == ".vtp") return SampleFormat::vtp;
  return SampleFormat::own;
}

// ---------------------------------------------------------------------------------------------
// Own format: see docs/sample.md. Text because samples are small next to the runs made from them,
// diffable and readable by any script; exact because every number is written as the shortest
// decimal that reads back to the same double; truncation-proof through the counts and the `end` line.

std::string format_own(const Sample& sample) {
  fmt::memory_buffer out;
  auto it = std::back_inserter(out);
  fmt::format_to(it, "rupture-sample {}\n", own_format_version);
  for (const auto& line : sample.provenance) fmt::format_to(it, "# {}\n", line);
  fmt::format_to(it,
                 "# units: lengths mm, density g/mm^3; groups: free, bottom (glued to the fixed plate), top "
                 "(glued to the moving plate)\n");
  const Box& b = sample.box;
  fmt::format_to(it, "box {} {} {} {} {} {}\n", b.lower.x, b.lower.y, b.lower.z, b.upper.x, b.upper.y,
                 b.upper.z);
  fmt::format_to(it, "density {}\n", sample.density);
  fmt::format_to(it, "particles {}\n# id x y z radius group\n", sample.size());
  for (const auto k : sample_detail::id_order(sample)) {
    const Vec3& p = sample.position[k];
    fmt::format_to(it, "{} {} {} {} {} {}\n", sample.id[k], p.x, p.y, p.z, sample.radius[k],
                   group_names[static_cast<std::size_t>(sample.group[k])]);
  }
  fmt::format_to(it, "bonds {}\n# id_a id_b rest_length\n", sample.bonds.size());
  for (const auto& bond : sample_detail::bonds_by_id(sample))
    fmt::format_to(it, "{} {} {}\n", bond.a, bond.b, bond.rest_length);
  fmt::format_to(it, "end\n");
  return fmt::to_string(out);
}

Sample parse_own(std::string_view text, const std::string& source) {
  TextReader in(text, source, 0, "see the layout of 'rupture-sample 1' in docs/sample.md");
  // Provenance comments come before `box`; the reader keeps them and skips every other comment.
  SampleAssembler build;
  std::string_view line;
  const auto next_data = [&](std::string_view what) {
    for (;;) {
      line = in.require(what);
      if (line.front() != '#') return tokens::words(line);
    }
  };
  auto words = tokens::words(in.require("the header 'rupture-sample 1'"));
  if (words.size() != 2 || words[0] != "rupture-sample")
    in.fail("not a rupture sample file (the first line must be 'rupture-sample <version>')");
  if (in.integer(words[1], "format version") != own_format_version)
    in.fail(fmt::format("format version {} is not supported (this rupture reads version {})", words[1],
                        own_format_version),
            "convert the file with the rupture version that wrote it");
  for (;;) {
    line = in.require("'box'");
    if (line.front() != '#') break;
    // The writer adds its own units line, so a comment that reads as one is not kept (whatever the
    // spacing after '#': the written file must read back to the same sample).
    const auto comment = tokens::trim(line.substr(1));
    if (!comment.starts_with("units:")) build.sample.provenance.emplace_back(comment);
  }
  words = tokens::words(line);
  if (words.size() != 7 || words[0] != "box") in.fail("expected 'box xlo ylo zlo xhi yhi zhi' (mm)");
  Box& box = build.sample.box;
  box.lower = {in.real(words[1], "box xlo"), in.real(words[2], "box ylo"), in.real(words[3], "box zlo")};
  box.upper = {in.real(words[4], "box xhi"), in.real(words[5], "box yhi"), in.real(words[6], "box zhi")};
  if (!(box.upper.x > box.lower.x && box.upper.y > box.lower.y && box.upper.z > box.lower.z))
    in.fail("box upper corner is not above the lower corner in every direction");
  words = next_data("'density'");
  if (words.size() != 2 || words[0] != "density") in.fail("expected 'density <g/mm^3>'");
  build.sample.density = in.real(words[1], "density");
  if (!(build.sample.density > 0.0)) in.fail("density must be positive (g/mm^3)");
  words = next_data("'particles'");
  if (words.size() != 2 || words[0] != "particles") in.fail("expected 'particles <count>'");
  const auto particles = in.count(words[1], "particle count");
  for (std::size_t k = 0; k < particles; ++k) {
    words = next_data(fmt::format("particle {} of {}", k + 1, particles));
    in.expect_columns(words, 6, "id x y z radius group");
    if (words.size() > 6) in.fail("more than 6 columns (id x y z radius group)");
    const auto group = std::find(group_names.begin(), group_names.end(), words[5]);
    if (group == group_names.end())
      in.fail(fmt::format("unknown group '{}'", excerpt(words[5])), "use free, bottom or top");
    build.add_particle(in, in.integer(words[0], "id"),
                       {in.real(words[1], "x"), in.real(words[2], "y"), in.real(words[3], "z")},
                       in.radius(words[4]), static_cast<ParticleGroup>(group - group_names.begin()));
  }
  words = next_data("'bonds'");
  if (words.size() != 2 || words[0] != "bonds")
    in.fail(fmt::format("expected 'bonds <count>' after {} particles", particles),
            "the particle count in the header must match the particle lines");
  const auto bonds = in.count(words[1], "bond count");
  for (std::size_t k = 0; k < bonds; ++k) {
    words = next_data(fmt::format("bond {} of {}", k + 1, bonds));
    in.expect_columns(words, 3, "id_a id_b rest_length");
    if (words.size() > 3) in.fail("more than 3 columns (id_a id_b rest_length)");
    build.add_bond(in, in.integer(words[0], "id_a"), in.integer(words[1], "id_b"),
                   in.real(words[2], "rest_length"));
  }
  words = next_data("'end'");
  if (words.size() != 1 || words[0] != "end")
    in.fail(fmt::format("expected 'end' after {} bonds", bonds),
            "the bond count in the header must match the bond lines");
  return build.finish();
}

// ---------------------------------------------------------------------------------------------
// VTK

io::VtkPolyData to_polydata(const Sample& sample) {
  io::VtkPolyData data;
  const auto order = sample_detail::id_order(sample);
  std::vector<std::uint32_t> rank(sample.size());
  std::vector<std::int64_t> ids, groups;
  std::vector<double> radii;
  for (std::uint32_t k = 0; k < order.size(); ++k) {
    const auto s = order[k];
    rank[s] = k;
    data.points.push_back(sample.position[s]);
    ids.push_back(sample.id[s]);
    radii.push_back(sample.radius[s]);
    groups.push_back(static_cast<std::int64_t>(sample.group[s]));
  }
  data.point_data = {
      {"id", 1, std::move(ids)}, {"radius", 1, std::move(radii)}, {"group", 1, std::move(groups)}};
  std::vector<double> rest;
  for (const Bond& b : sample.bonds) {
    data.lines.push_back({rank[b.i], rank[b.j]});
    rest.push_back(b.rest_length);
  }
  data.line_data = {{"rest_length", 1, std::move(rest)}};
  data.comments = sample.provenance;
  data.comments.push_back(
      "rupture sample: points = particles (radius mm; group 0 free, 1 bottom, 2 top), lines = bonds "
      "(rest_length mm)");
  return data;
}

// ---------------------------------------------------------------------------------------------
// Dispatch

Sample load_sample(const fs::path& path) {
  const std::string source = path.string();
  // A .vtp (binary since it is zlib-compressed) is refused for what it is, not for its NUL bytes.
  if (sample_format_for_path(path) == SampleFormat::vtp)
    throw InputError(source, "a .vtp file is a picture of a sample, not a sample",
                     "load the sample file it was written from (own, LAMMPS data or LSMGeometry)");
  const std::string text = io::read_text_file(path);
  const auto first_line = tokens::trim(std::string_view(text).substr(0, text.find('\n')));
  Sample sample;
  if (first_line.starts_with("rupture-sample")) {
    sample = parse_own(text, source);
  } else if (first_line.starts_with("LSMGeometry")) {
    sample = parse_lsm_geometry(text, source);
  } else if (sample_format_for_path(path) == SampleFormat::lammps ||
             text.find(" atoms\n") != std::string::npos) {
    sample = parse_lammps_data(text, source);
  } else {
    throw InputError(source + ":1", "not a sample file rupture knows",
                     "give a rupture sample ('rupture-sample 1'), a LAMMPS data file (.data/.lmp) or an "
                     "ESyS-Particle geometry ('LSMGeometry 1.2')");
  }
  if (sample.size() == 0) throw InputError(source, "the sample has no particles");
  return sample;
}

void save_sample(const Sample& sample, const fs::path& path) {
  save_sample(sample, path, sample_format_for_path(path));
}

void save_sample(const Sample& sample, const fs::path& path, SampleFormat format) {
  switch (format) {
    case SampleFormat::own:
      io::write_file_atomically(path, format_own(sample));
      break;
    case SampleFormat::lammps:
      io::write_file_atomically(path, format_lammps_data(sample));
      break;
    case SampleFormat::lsm:
      io::write_file_atomically(path, format_lsm_geometry(sample));
      break;
    case SampleFormat::vtp:
      io::write_vtp(path, to_polydata(sample));
      break;
  }
}

}  // namespace rupture
