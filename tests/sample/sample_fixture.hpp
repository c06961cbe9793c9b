// tests/sample/sample_fixture: the reduced tissue the sample tests share, generated once per process.
#pragma once

#include "sample/presets.hpp"

namespace rupture::testing {

struct GeneratedTissue {
  Sample sample;
  GenerationReport report;
};

inline const GeneratedTissue& small_tissue() {
  static const GeneratedTissue tissue = [] {
    GeneratedTissue t;
    t.sample = make_preset("tissue-small", 42, &t.report);
    return t;
  }();
  return tissue;
}

}  // namespace rupture::testing
