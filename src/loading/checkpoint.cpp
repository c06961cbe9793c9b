#include "loading/checkpoint.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <cstring>
#include <type_traits>

#include "core/error.hpp"
#include "core/hash.hpp"
#include "io/atomic_file.hpp"

namespace rupture::loading {

namespace fs = std::filesystem;

namespace {

static_assert(std::endian::native == std::endian::little,
              "checkpoints store numbers little-endian as they lie in memory");

constexpr char magic[8] = {'R', 'U', 'P', 'T', 'C', 'K', 'P', 'T'};
// magic, format version (u32), payload size (u64); the checksum (u64) follows the payload.
constexpr std::size_t header_size = sizeof magic + 4 + 8, checksum_size = 8;

const std::string reader_fix = "resume from an older checkpoint, or start the run again";

// Appends fields to the payload. Vectors and strings carry their element count first.
class Writer {
 public:
  explicit Writer(std::string& out) : out_(out) {}
  template <class T>
  void operator()(const char*, const T& value) {
    if constexpr (std::is_same_v<T, std::string>) {
      scalar(std::uint64_t(value.size()));
      out_.append(value);
    } else if constexpr (std::is_same_v<T, bool>) {
      scalar(std::uint8_t(value ? 1 : 0));
    } else if constexpr (std::is_arithmetic_v<T>) {
      scalar(value);
    } else {  // std::vector of numbers
      scalar(std::uint64_t(value.size()));
      out_.append(reinterpret_cast<const char*>(value.data()), value.size() * sizeof(value[0]));
    }
  }

 private:
  template <class T>
  void scalar(T value) {
    out_.append(reinterpret_cast<const char*>(&value), sizeof value);
  }
  std::string& out_;
};

// Reads fields back, refusing anything that would reach past the payload.
class Reader {
 public:
  Reader(std::string_view payload, const std::string& source) : data_(payload), source_(source) {}
  template <class T>
  void operator()(const char* field, T& value) {
    if constexpr (std::is_same_v<T, std::string>) {
      const std::uint64_t size = count(field, 1);
      value.assign(take(field, size), size);
    } else if constexpr (std::is_same_v<T, bool>) {
      std::uint8_t flag = 0;
      std::memcpy(&flag, take(field, 1), 1);
      if (flag > 1) fail(field, fmt::format("holds {} where 0 or 1 belongs", flag));
      value = flag != 0;
    } else if constexpr (std::is_arithmetic_v<T>) {
      std::memcpy(&value, take(field, sizeof value), sizeof value);
    } else {
      using Element = typename T::value_type;
      const std::uint64_t size = count(field, sizeof(Element));
      value.resize(size);
      if (size > 0) std::memcpy(value.data(), take(field, size * sizeof(Element)), size * sizeof(Element));
    }
  }
  void finish() const {
    if (at_ != data_.size())
      fail("payload", fmt::format("{} bytes are left over after the last field", data_.size() - at_));
  }
  [[noreturn]] void fail(const std::string& field, const std::string& problem) const {
    throw InputError(source_ + ": " + field, problem, reader_fix);
  }

 private:
  // An element count, checked against the bytes left before anything is allocated.
  std::uint64_t count(const char* field, std::size_t element_size) {
    std::uint64_t n = 0;
    std::memcpy(&n, take(field, sizeof n), sizeof n);
    if (n > (data_.size() - at_) / element_size)
      fail(field,
           fmt::format("claims {} entries but only {} bytes are left (truncated?)", n, data_.size() - at_));
    return n;
  }
  const char* take(const char* field, std::size_t size) {
    if (size > data_.size() - at_) fail(field, "ends early (the file is truncated)");
    const char* p = data_.data() + at_;
    at_ += size;
    return p;
  }
  std::string_view data_;
  std::size_t at_ = 0;
  const std::string& source_;
};

// Every field in file order; the one list that both the writer and the reader walk.
template <class Io, class C>
void visit_fields(Io& io, C& c) {
  io("version", c.version);
  io("command", c.command);
  io("config_file", c.config_file);
  io("config", c.config_json);
  io("sample_fingerprint", c.sample_fingerprint);
  auto& l = c.loop;
  io("curves_bytes", l.curves_bytes);
  io("curves_rows", l.curves_rows);
  io("breaks_bytes", l.breaks_bytes);
  if (c.format >= 2) {
    io("curves_hash", l.curves_hash);
    io("breaks_hash", l.breaks_hash);
  }
  io("last_recorded", l.last_recorded);
  io("max_work", l.max_work);
  io("max_energy_error", l.max_energy_error);
  io("max_relative_energy_error", l.max_relative_energy_error);
  io("separated", l.separated);
  io("separation_strain", l.separation_strain);
  io("separation_rule", l.separation_rule);
  auto& free = l.load_free;
  io("load_free.sum", free.sum);
  io("load_free.count", free.count);
  io("load_free.last_strain", free.last_strain);
  io("load_free.peak", free.peak);
  io("load_free.load_free", free.load_free);
  io("load_free.free_since", free.free_since);
  io("wall_seconds", l.wall_seconds);
  if (c.format >= 3) {
    io("row_means.strain", l.row_means.strain);
    io("row_means.force_top", l.row_means.force_top);
    io("row_means.elastic_energy", l.row_means.elastic_energy);
    io("row_means.samples", l.row_means.samples);
  }
  auto& e = c.engine;
  io("step", e.step);
  io("time", e.time);
  io("top.displacement", e.top.displacement);
  io("top.velocity", e.top.velocity);
  io("top.acceleration", e.top.acceleration);
  for (auto& f : e.plate_force) io("plate_force", f);
  io("plate_work", e.plate_work);
  io("released", e.released);
  io("damped", e.damped);
  io("neighbour_rebuilds", e.neighbour_rebuilds);
  io("forces_stale", e.forces_stale);
  auto& t = e.stage_times;
  for (auto* seconds : {&t.neighbours, &t.integrate, &t.forces, &t.plates, &t.breaks})
    io("stage_times", *seconds);
  io("sample_of_storage", e.sample_of_storage);
  io("x", e.x);
  io("y", e.y);
  io("z", e.z);
  io("vx", e.vx);
  io("vy", e.vy);
  io("vz", e.vz);
  io("fx", e.fx);
  io("fy", e.fy);
  io("fz", e.fz);
  io("xb", e.xb);
  io("yb", e.yb);
  io("zb", e.zb);
  io("damped_per_particle", e.damped_per_particle);
  io("intact", e.intact);
  io("link_count", e.link_count);
  io("link_bond", e.link_bond);
  io("nb_start", e.nb_start);
  io("nb_count", e.nb_count);
  io("nb", e.nb);
}

// Snapshots (time and file name) go last: a count, then each entry.
void write_snapshots(Writer& w, const std::vector<io::PvdEntry>& snapshots) {
  w("snapshots", std::uint64_t(snapshots.size()));
  for (const auto& s : snapshots) {
    w("snapshot.time", s.time);
    w("snapshot.file", s.file.string());
  }
}

void read_snapshots(Reader& r, std::vector<io::PvdEntry>& snapshots) {
  std::uint64_t n = 0;
  r("snapshots", n);
  snapshots.clear();
  for (std::uint64_t i = 0; i < n; ++i) {  // each entry takes >= 16 bytes, so n is bounded by take()
    io::PvdEntry entry;
    std::string file;
    r("snapshot.time", entry.time);
    r("snapshot.file", file);
    entry.file = file;
    snapshots.push_back(std::move(entry));
  }
}

}  // namespace

std::uint64_t sample_fingerprint(const Sample& sample) {
  Fnv1a h;
  h.add_value(std::uint64_t(sample.size()));
  for (const Vec3& p : sample.position)
    for (double v : {p.x, p.y, p.z}) h.add_value(v);
  h.add_vector(sample.radius);
  for (const auto g : sample.group) h.add_value(static_cast<std::uint8_t>(g));
  for (const auto id : sample.id) h.add_value(std::int64_t(id));
  h.add_value(std::uint64_t(sample.bonds.size()));
  for (const auto& b : sample.bonds) {
    h.add_value(std::uint64_t(b.i));
    h.add_value(std::uint64_t(b.j));
    h.add_value(b.rest_length);
  }
  h.add_value(sample.density);
  return h.hash;
}

std::string encode_checkpoint(const Checkpoint& checkpoint) {
  std::string payload;
  Writer writer(payload);
  visit_fields(writer, checkpoint);
  write_snapshots(writer, checkpoint.loop.snapshots);
  std::string out(magic, sizeof magic);
  Writer header(out);
  header("version", checkpoint.format);
  header("payload_size", std::uint64_t(payload.size()));
  out += payload;
  Fnv1a h;
  h.add(out.data(), out.size());
  header("checksum", h.hash);
  return out;
}

Checkpoint parse_checkpoint(std::string_view bytes, const std::string& source) {
  const auto fail = [&](const std::string& field, const std::string& problem) {
    throw InputError(source + ": " + field, problem, reader_fix);
  };
  if (bytes.size() < header_size + checksum_size)
    fail("header", fmt::format("{} bytes is too short for a checkpoint (truncated?)", bytes.size()));
  if (std::memcmp(bytes.data(), magic, sizeof magic) != 0) fail("magic", "not a rupture checkpoint");
  std::uint32_t version = 0;
  std::uint64_t payload_size = 0, stored = 0;
  std::memcpy(&version, bytes.data() + sizeof magic, sizeof version);
  std::memcpy(&payload_size, bytes.data() + sizeof magic + 4, sizeof payload_size);
  if (version < 1 || version > checkpoint_format_version)
    fail("version", fmt::format("format version {} is not one this rupture reads (1 to {})", version,
                                checkpoint_format_version));
  if (payload_size != bytes.size() - header_size - checksum_size)
    fail("payload_size", fmt::format("says {} bytes but the file holds {} (truncated or appended to?)",
                                     payload_size, bytes.size() - header_size - checksum_size));
  std::memcpy(&stored, bytes.data() + bytes.size() - checksum_size, sizeof stored);
  Fnv1a h;
  h.add(bytes.data(), bytes.size() - checksum_size);
  if (h.hash != stored)
    fail("checksum",
         fmt::format("is {:016x} but the content hashes to {:016x} (the file is corrupt)", stored, h.hash));
  Checkpoint checkpoint;
  checkpoint.format = version;
  Reader reader(bytes.substr(header_size, payload_size), source);
  visit_fields(reader, checkpoint);
  read_snapshots(reader, checkpoint.loop.snapshots);
  reader.finish();
  return checkpoint;
}

void write_checkpoint(const fs::path& path, const Checkpoint& checkpoint) {
  io::write_file_atomically(path, encode_checkpoint(checkpoint));
}

Checkpoint read_checkpoint(const fs::path& path) {
  return parse_checkpoint(io::read_file(path), path.string());
}

fs::path checkpoint_path(const fs::path& folder, std::uint64_t step) {
  return folder / "checkpoints" / fmt::format("step_{:010d}.ckpt", step);
}

std::vector<fs::path> list_checkpoints(const fs::path& folder) {
  std::vector<std::pair<std::uint64_t, fs::path>> found;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(folder / "checkpoints", ec)) {
    const std::string name = entry.path().filename().string();
    if (name.size() != 20 || !name.starts_with("step_") || !name.ends_with(".ckpt")) continue;
    const std::string digits = name.substr(5, 10);
    if (!std::all_of(digits.begin(), digits.end(), [](char ch) { return ch >= '0' && ch <= '9'; })) continue;
    found.emplace_back(std::stoull(digits), entry.path());
  }
  std::sort(found.begin(), found.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  std::vector<fs::path> files;
  for (auto& [step, path] : found) files.push_back(std::move(path));
  return files;
}

fs::path save_checkpoint(const fs::path& folder, const Checkpoint& checkpoint, std::size_t keep) {
  const fs::path file = checkpoint_path(folder, checkpoint.engine.step);
  fs::create_directories(file.parent_path());
  write_checkpoint(file, checkpoint);
  // Only once the new one is safely in place do the oldest go.
  const auto files = list_checkpoints(folder);
  for (std::size_t i = keep; i < files.size(); ++i) {
    std::error_code ignored;
    fs::remove(files[i], ignored);
  }
  return file;
}

LoadedCheckpoint load_newest_checkpoint(const fs::path& folder) {
  LoadedCheckpoint loaded;
  for (const auto& file : list_checkpoints(folder)) {
    try {
      loaded.checkpoint = read_checkpoint(file);
      loaded.file = file;
      return loaded;
    } catch (const InputError& e) {
      loaded.warnings.push_back(fmt::format("skipping unreadable checkpoint: {}", e.what()));
    }
  }
  throw InputError((folder / "checkpoints").string(),
                   loaded.warnings.empty() ? "holds no checkpoint" : "holds no readable checkpoint",
                   "a run writes checkpoints every checkpoint.every steps or checkpoint.minutes of "
                   "wall time; start the run again");
}

}  // namespace rupture::loading
