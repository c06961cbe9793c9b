// System::save_state and System::restore_state: the engine's state to and from EngineState.
#include <algorithm>
#include <string>
#include <utility>

#include "core/error.hpp"
#include "dem/system.hpp"

namespace rupture::dem {

EngineState System::save_state() const {
  const HotParticles& p = particles_.hot;
  EngineState s;
  s.step = step_;
  s.time = time_;
  s.top = top_;
  s.plate_force = ledger_.plate_force;
  s.plate_work = ledger_.plate_work;
  s.released = ledger_.released;
  s.damped = ledger_.damped;
  s.neighbour_rebuilds = neighbours_.builds;
  s.forces_stale = forces_stale_;
  s.stage_times = times_;
  s.sample_of_storage = particles_.sample_of_storage;
  s.x = p.x, s.y = p.y, s.z = p.z;
  s.vx = p.vx, s.vy = p.vy, s.vz = p.vz;
  s.fx = p.fx, s.fy = p.fy, s.fz = p.fz;
  s.xb = neighbours_.xb, s.yb = neighbours_.yb, s.zb = neighbours_.zb;
  s.damped_per_particle = particles_.cold.damped;
  s.intact = bonds_.intact;
  s.link_count = bonds_.link_count;
  s.link_bond = bonds_.link_bond;
  s.nb_start = neighbours_.start;
  s.nb_count = neighbours_.count;
  // Slots past each slice's used part hold leftovers of older lists that are never read: zero them so
  // that equal states give equal checkpoint bytes.
  s.nb.assign(neighbours_.list.size(), 0);
  for (std::size_t a = 0; a < size(); ++a)
    std::copy_n(neighbours_.list.begin() + neighbours_.start[a], neighbours_.count[a],
                s.nb.begin() + neighbours_.start[a]);
  return s;
}

namespace {

// Checks a checkpoint's engine state against the engine it is restored into; every failure names
// the checkpoint and the field.
struct StateCheck {
  const EngineState& s;
  const std::string& source;

  [[noreturn]] void fail(const std::string& field, const std::string& problem) const {
    throw InputError(source + ": " + field, problem,
                     "resume with the sample and config the checkpoint was written with, or use an older "
                     "checkpoint");
  }
  void require_size(const std::string& field, std::size_t size, std::size_t expected) const {
    if (size != expected)
      fail(field, "holds " + std::to_string(size) + " values where this run has " + std::to_string(expected));
  }

  void sizes(const ParticleStore& particles, const BondStore& bonds) const {
    const std::size_t n = particles.hot.x.size();
    if (s.sample_of_storage != particles.sample_of_storage)
      fail("sample_of_storage", "the particle order differs from this sample's (another sample?)");
    const std::pair<const char*, const std::vector<double>*> particle_fields[] = {
        {"x", &s.x},
        {"y", &s.y},
        {"z", &s.z},
        {"vx", &s.vx},
        {"vy", &s.vy},
        {"vz", &s.vz},
        {"fx", &s.fx},
        {"fy", &s.fy},
        {"fz", &s.fz},
        {"xb", &s.xb},
        {"yb", &s.yb},
        {"zb", &s.zb},
        {"damped_per_particle", &s.damped_per_particle}};
    for (const auto& [name, values] : particle_fields) require_size(name, values->size(), n);
    require_size("intact", s.intact.size(), bonds.size());
    require_size("link_count", s.link_count.size(), n);
    require_size("link_bond", s.link_bond.size(), bonds.link_bond.size());
    require_size("nb_start", s.nb_start.size(), n + 1);
    require_size("nb_count", s.nb_count.size(), n);
  }

  // Each particle's slice must hold its own bonds (in any order), the intact ones first.
  void links(const BondStore& bonds) const {
    for (std::size_t b = 0; b < bonds.size(); ++b)
      if (s.intact[b] > 1)
        fail("intact", "bond " + std::to_string(b) + " has flag " + std::to_string(s.intact[b]));
    std::vector<std::uint32_t> mine, theirs;
    for (std::size_t a = 0; a + 1 < bonds.link_start.size(); ++a) {
      const std::uint32_t begin = bonds.link_start[a], end = bonds.link_start[a + 1];
      if (s.link_count[a] > end - begin)
        fail("link_count", "particle slot " + std::to_string(a) + " counts more links than it has");
      mine.assign(bonds.link_bond.begin() + begin, bonds.link_bond.begin() + end);
      theirs.assign(s.link_bond.begin() + begin, s.link_bond.begin() + end);
      std::sort(mine.begin(), mine.end());
      std::sort(theirs.begin(), theirs.end());
      if (mine != theirs)
        fail("link_bond", "particle slot " + std::to_string(a) + " lists bonds it does not have");
      for (std::uint32_t l = begin; l < end; ++l)
        if ((l < begin + s.link_count[a]) != (s.intact[s.link_bond[l]] != 0))
          fail("link_count", "particle slot " + std::to_string(a) + " disagrees with the intact flags");
    }
  }

  void neighbours(std::size_t n) const {
    if (s.nb_start[0] != 0) fail("nb_start", "does not start at 0");
    for (std::size_t a = 0; a < n; ++a) {
      if (s.nb_start[a + 1] < s.nb_start[a])
        fail("nb_start", "decreases at particle slot " + std::to_string(a));
      if (s.nb_count[a] > s.nb_start[a + 1] - s.nb_start[a])
        fail("nb_count", "particle slot " + std::to_string(a) + " overflows its neighbour slice");
    }
    require_size("nb", s.nb.size(), s.nb_start[n]);
    for (std::size_t a = 0; a < n; ++a)
      for (std::uint32_t q = s.nb_start[a]; q < s.nb_start[a] + s.nb_count[a]; ++q)
        if (s.nb[q] >= n || s.nb[q] == a)
          fail("nb", "particle slot " + std::to_string(a) + " has an invalid neighbour");
  }
};

}  // namespace

void System::restore_state(const EngineState& s, const std::string& source) {
  const StateCheck check{s, source};
  check.sizes(particles_, bonds_);
  check.links(bonds_);
  check.neighbours(size());

  step_ = s.step;
  time_ = s.time;
  top_ = s.top;
  ledger_.plate_force = s.plate_force;
  ledger_.plate_work = s.plate_work;
  ledger_.released = s.released;
  ledger_.damped = s.damped;
  neighbours_.builds = s.neighbour_rebuilds;
  forces_stale_ = s.forces_stale;
  measured_.reset();
  times_ = s.stage_times;
  HotParticles& p = particles_.hot;
  p.x = s.x, p.y = s.y, p.z = s.z;
  p.vx = s.vx, p.vy = s.vy, p.vz = s.vz;
  p.fx = s.fx, p.fy = s.fy, p.fz = s.fz;
  neighbours_.xb = s.xb, neighbours_.yb = s.yb, neighbours_.zb = s.zb;
  particles_.cold.damped = s.damped_per_particle;
  bonds_.restore(s.intact, s.link_count, s.link_bond);
  neighbours_.start = s.nb_start;
  neighbours_.count = s.nb_count;
  neighbours_.list = s.nb;
  breaks_.events.clear();
  last_move_ = {};
}

}  // namespace rupture::dem
