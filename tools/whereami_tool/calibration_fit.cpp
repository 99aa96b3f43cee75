#include "whereami_tool/calibration_fit.h"

#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "common/input_error.h"

namespace stickrep::whereami {
namespace {

// The value at `key` of `j`, of the JSON type `is` checks, or an InputError naming it.
const nlohmann::json& Required(const nlohmann::json& j, const std::string& file,
                               const std::string& key, bool (nlohmann::json::*is)() const noexcept,
                               const char* expected) {
  const auto it = j.find(key);
  if (it == j.end()) {
    throw InputError(file, 0, key, "missing (a batch written by stickrep-whereami --json)");
  }
  if (!((*it).*is)()) throw InputError(file, 0, key, fmt::format("expected {}", expected));
  return *it;
}

std::vector<ConfidenceSample> SamplesOf(const nlohmann::json& batch, const std::string& file,
                                        int* runs) {
  std::vector<ConfidenceSample> samples;
  const nlohmann::json& run_list =
      Required(batch, file, "runs", &nlohmann::json::is_array, "an array of runs");
  *runs = static_cast<int>(run_list.size());
  for (std::size_t i = 0; i < run_list.size(); ++i) {
    const std::string key = fmt::format("runs[{}].confidences", i);
    const auto it = run_list[i].find("confidences");
    if (it == run_list[i].end() || !it->is_array()) {
      throw InputError(file, 0, key, "missing or not an array (written by an older build?)");
    }
    for (const nlohmann::json& c : *it) {
      const auto confidence = c.find("confidence");
      const auto correct = c.find("correct");
      const auto localized = c.find("localized");
      if (!c.is_object() || confidence == c.end() || !confidence->is_number() ||
          correct == c.end() || !correct->is_boolean() ||
          (localized != c.end() && !localized->is_boolean()) ||
          !(*confidence >= 0.0 && *confidence <= 1.0)) {
        throw InputError(file, 0, key,
                         "each sample needs a confidence in [0, 1], a true/false correct and "
                         "at most a true/false localized");
      }
      ConfidenceSample s;
      s.confidence = confidence->get<double>();
      s.correct = correct->get<bool>();
      s.localized = localized != c.end() && localized->get<bool>();
      samples.push_back(s);
    }
  }
  return samples;
}

}  // namespace

localizer::ConfidenceCalibration ComposeCalibration(
    const localizer::ConfidenceCalibration& ran_under, const Reliability::Fit& fit) {
  localizer::ConfidenceCalibration c;
  c.slope = fit.slope * ran_under.slope;
  c.offset = fit.slope * ran_under.offset + fit.offset;
  return c;
}

PooledCalibrationFit FitCalibrationFromBatches(const std::vector<std::string>& files) {
  if (files.empty()) throw InputError("-", 0, "--fit-calibration", "names no batch file");
  PooledCalibrationFit pooled;
  std::vector<ConfidenceSample> all;
  for (const std::string& file : files) {
    std::ifstream in(file);
    if (!in) throw InputError(file, 0, "--fit-calibration", "cannot be read");
    nlohmann::json batch;
    try {
      batch = nlohmann::json::parse(in);
    } catch (const nlohmann::json::parse_error& e) {
      throw InputError(file, 0, "--fit-calibration", fmt::format("not JSON: {}", e.what()));
    }
    const nlohmann::json& cal =
        Required(batch, file, "calibration", &nlohmann::json::is_object, "an object");
    localizer::ConfidenceCalibration ran_under;
    ran_under.slope = Required(cal, file, "slope", &nlohmann::json::is_number, "a number");
    ran_under.offset = Required(cal, file, "offset", &nlohmann::json::is_number, "a number");
    const double bar =
        Required(cal, file, "localized_confidence", &nlohmann::json::is_number, "a number");
    if (pooled.batches.empty()) {
      pooled.ran_under = ran_under;
      pooled.localized_confidence = bar;
    } else if (std::abs(ran_under.slope - pooled.ran_under.slope) > 1e-9 ||
               std::abs(ran_under.offset - pooled.ran_under.offset) > 1e-9 ||
               std::abs(bar - pooled.localized_confidence) > 1e-9) {
      throw InputError(file, 0, "calibration",
                       fmt::format("ran under slope {:g}, offset {:g}, bar {:g}, where {} ran "
                                   "under {:g}, {:g}, {:g}: one fit composes with one calibration",
                                   ran_under.slope, ran_under.offset, bar, pooled.batches[0].file,
                                   pooled.ran_under.slope, pooled.ran_under.offset,
                                   pooled.localized_confidence));
    }
    PooledCalibrationFit::Batch b;
    b.file = file;
    b.map = Required(batch, file, "map", &nlohmann::json::is_string, "a string");
    const std::vector<ConfidenceSample> samples = SamplesOf(batch, file, &b.runs);
    b.samples = static_cast<int>(samples.size());
    b.fit = FitPlatt(samples);
    all.insert(all.end(), samples.begin(), samples.end());
    pooled.batches.push_back(b);
  }
  pooled.fit = FitPlatt(all);
  pooled.composed = ComposeCalibration(pooled.ran_under, pooled.fit);
  return pooled;
}

void PrintPooledCalibrationFit(const PooledCalibrationFit& f, std::ostream& out) {
  out << fmt::format(
      "Platt fit of the published confidence, logit(right) = a logit(c) + b, "
      "under the calibration slope {:.3f}, offset {:+.3f}:\n",
      f.ran_under.slope, f.ran_under.offset);
  for (const PooledCalibrationFit::Batch& b : f.batches) {
    out << fmt::format("  {:<24} {:>5} runs {:>6} samples  a {:.3f}  b {:+.3f}   {}\n", b.map,
                       b.runs, b.samples, b.fit.slope, b.fit.offset, b.file);
  }
  int runs = 0;
  for (const PooledCalibrationFit::Batch& b : f.batches) runs += b.runs;
  out << fmt::format("  {:<24} {:>5} runs {:>6} samples  a {:.3f}  b {:+.3f}\n", "pooled", runs,
                     f.fit.n, f.fit.slope, f.fit.offset);
  out << fmt::format(
      "taken through that calibration: confidence_calibration_slope {:.3f}, "
      "confidence_calibration_offset {:+.3f}; the bar {:g} is then the posterior "
      "{:.6f} (it was {:.6f})\n",
      f.composed.slope, f.composed.offset, f.localized_confidence,
      f.composed.PosteriorFor(f.localized_confidence),
      f.ran_under.PosteriorFor(f.localized_confidence));
}

}  // namespace stickrep::whereami
