// tests/figures/scan_fixture: a small scan folder written by hand (results.csv with ten points and
// their known classes, Γ and δ_x), so the scan figures and the scan report are tested without running
// a scan. Shared by tests/figures and tests/report.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <vector>

#include "io/atomic_file.hpp"
#include "scan/results.hpp"

namespace rupture::testing {

// Counts the fixture holds, for the tests to check the figures against.
struct ScanFixture {
  static constexpr int points = 10;
  static constexpr int brittle = 2, hyper_elastic = 1, semi_ductile = 3;
  static constexpr int rejected_ductile = 1, rejected_other = 1;  // separated, rejected: no class
  static constexpr int without_class = 2;                         // one not separated, one failed
  static constexpr int gamma_above_5 = 2;  // stars in figure 15, the Γ > 5 group of figure 17
  static constexpr int gamma_below_1 = 2, gamma_1_to_5 = 2;
  static constexpr int positive_delay = 5;  // analysed with δ_x > 0: drawn in figure 16
  static constexpr int negative_delay = 1;  // analysed with δ_x < 0: counted in figure 16's title
};

// Writes FOLDER/results.csv (and a scan.json) for a 2 x 4 grid of (k_n, b_d).
inline void write_scan_fixture(const std::filesystem::path& folder) {
  using nlohmann::json;
  std::filesystem::create_directories(folder);
  // k_n [N/mm], b_d [mm], status, class, x_c [%], δ_x [%], Γ, A_r
  struct Row {
    double k_n, b_d;
    const char* status;
    const char* mechanism;
    double x_c, delta_x, gamma, a_r;
  };
  const Row table[] = {
      {1e2, 1e-3, "ok", "brittle", 0.05, 0.012, 0.4, 1.30},
      {1e4, 1e-3, "ok", "brittle", 0.02, 0.006, 0.8, 1.25},
      {1e2, 1e-2, "ok", "hyper-elastic", 0.6, 0.15, 2.0, 1.10},
      {1e4, 1e-2, "ok", "semi-ductile", 0.3, 0.08, 3.5, 0.95},
      {1e2, 1e-1, "ok", "semi-ductile", 5.0, 0.9, 7.0, 0.80},
      {1e4, 1e-1, "ok", "semi-ductile", 2.0, -0.1, 12.0, 0.70},
      {1e3, 1e-1, "ok",
       "rejected: ductile-like breaking, x_c not identifiable: 4 significant force maxima (>= 3)", 0, 0, 0,
       0},
      {1e3, 1e-2, "ok", "rejected: δ_x too uncertain", 0, 0, 0, 0},
      {1e2, 1.0, "no_separation", "", 0.0, 0.0, 0.0, 0.0},
      {1e4, 1.0, "error", "", 0.0, 0.0, 0.0, 0.0},
  };
  std::vector<json> rows;
  int point = 0;
  for (const auto& r : table) {
    json row = {{"point", point++}, {"k_n", r.k_n}, {"b_d", r.b_d}, {"status", r.status}};
    if (const std::string mechanism = r.mechanism; mechanism.rfind("rejected: ", 0) == 0) {
      row.update({{"accepted", 0}, {"why", mechanism.substr(10)}});
    } else if (std::string(r.status) == "ok") {
      row.update({{"class", r.mechanism},
                  {"accepted", 1},
                  {"x_c", r.x_c},
                  {"x_c_err", 0.02 * r.x_c},
                  {"x_p", r.x_c - r.delta_x},
                  {"delta_x", r.delta_x},
                  {"delta_x_sd", 0.1 * std::abs(r.delta_x)},
                  {"delta_x_lo68", r.delta_x - 0.1 * std::abs(r.delta_x)},
                  {"delta_x_hi68", r.delta_x + 0.1 * std::abs(r.delta_x)},
                  {"Gamma", r.gamma},
                  {"A_r", r.a_r},
                  {"A_r_err", 0.05}});
    } else {
      row["why"] = std::string(r.status) == "error" ? "energy balance broke down, see run.json"
                                                    : "still whole at max_strain";
    }
    rows.push_back(std::move(row));
  }
  io::write_file_atomically(folder / "results.csv", scan::format_results(rows, {"rupture test fixture"}));
  io::write_json_atomically(folder / "scan.json",
                            json{{"tool", "rupture scan"}, {"grid", {{"k_n", {1e2, 1e4}}}}});
}

}  // namespace rupture::testing
