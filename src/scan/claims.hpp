// scan/claims: the paper's findings of section 5 checked one by one against a scan's results table —
// δ_x > 0, δ_x against x_c, the α that δ_x/x_c implies, A_r in the FBM band, the far events, where the
// brittle class lies and the share rejected. One text for the scan report, the study report and
// `rupture scan --claims` (docs/study.md). Not: reading or writing the table (scan/results).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "scan/results.hpp"

namespace rupture::scan {

struct Claim {
  std::string paper;  // the paper's claim, in its words
  std::string here;   // what this scan shows
};

struct Claims {
  std::size_t points = 0;     // rows of results.csv
  std::size_t ran = 0;        // finished (any status but pending and running)
  std::size_t separated = 0;  // status ok: the sample came apart and the curve was analysed
  std::size_t accepted = 0;   // separated and accepted by the analysis
  std::vector<Claim> rows;
  std::string counts() const;  // "48 points: 48 ran, 46 separated, 40 accepted, ..."
};

Claims check_claims(const ResultsTable& table);

// "### TITLE", the counts and the claims as a markdown table.
std::string claims_markdown(const Claims& claims, const std::string& title);

}  // namespace rupture::scan
