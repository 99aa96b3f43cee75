#include "sensing_tool/sensing_report.h"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <stdexcept>

#include "common/units.h"
#include "sensing/door_classifier.h"

namespace stickrep::sensing {

namespace {

constexpr double kStaresDeg[3] = {90.0, 70.0, 50.0};

// The paper's figures, by stare 90°, 70°, 50°.
constexpr double kPaperTable52[3][4] = {
    {2.0, 2.0, 4.3, 5.1}, {4.1, 0.57, 15.0, 2.1}, {9.1, 0.72, 21.0, 1.5}};
constexpr double kPaperTable53TwoSide[3] = {2.4, 3.9, 4.7};
constexpr double kPaperTable53ShortSide[3] = {0.40, 5.5, 12.0};
constexpr double kPaperTable54[3] = {0.28, 3.2, 6.6};
constexpr double kPaperTable55Deg[3] = {57.0, 1.8, 0.5};
constexpr double kPaperTable56[3] = {0.92, 0.41, 0.16};

template <typename T>
T Must(Result<T> r, const std::string& what) {
  if (!r) throw std::runtime_error(what + ": " + r.message());
  return *r;
}

std::string Ratio(double ours, double paper) {
  if (paper == 0.0) return "   -";
  return fmt::format("{:+5.0f}%", 100.0 * (ours - paper) / paper);
}

nlohmann::json TermsJson(const LinearEstimate& e) {
  nlohmann::json terms = nlohmann::json::array();
  for (const LinearTerm& t : e.terms) {
    terms.push_back({{"input", t.input},
                     {"partial", t.partial},
                     {"delta", t.delta},
                     {"contribution_in", t.contribution_in}});
  }
  return terms;
}

std::string FigureName(Geometry g, double stare_deg) {
  static const char* kFig[2][3] = {{"figure_5_7", "figure_5_8", "figure_5_9"},
                                   {"figure_5_4", "figure_5_5", "figure_5_6"}};
  const int s = stare_deg == 90.0 ? 0 : (stare_deg == 70.0 ? 1 : 2);
  return fmt::format("{}_{}_{:.0f}deg", kFig[g == Geometry::kShortSide][s],
                     g == Geometry::kShortSide ? "short_side" : "two_side", stare_deg);
}

StareScene SceneAt(const ReportOptions& opt, double stare_deg) {
  StareScene s;
  s.wall_distance_in = opt.wall_distance_in;
  s.stare_rad = DegToRad(stare_deg);
  s.door_width_in = opt.door_width_in;
  s.door_offset_in = opt.door_offset_in;
  return s;
}

// The report's heading: the free parameters and the camera.
void AddParameters(const RobotConfig& robot, const ReportOptions& opt, SensingReport& rep) {
  std::string& out = rep.text;
  out += "StickRep sensing report: Chapter 5 of the dissertation, ours beside the paper's\n";
  out += fmt::format(
      "seed {}  trials {}  wall {:.1f} in  door {:.1f} in (offset {:.1f} in)  short side {}\n",
      opt.seed, opt.trials, opt.wall_distance_in, opt.door_width_in, opt.door_offset_in,
      opt.edges == ShortSideEdges::kPaperSensorRays ? "as printed (30 deg sensor rays)"
                                                    : "field-of-view edges");
  out += fmt::format(
      "camera: FOV {:.3f} deg, {} px wide, f {:.2f} mm, pitch {:.6f} mm; bounds: dtheta {:.2f} "
      "deg, dLJ=dRJ {:.1f} px, surface {}\n\n",
      robot.camera.fov_deg, robot.camera.image_width_px, robot.camera.focal_length_mm,
      robot.camera.pixel_pitch_mm, RadToDeg(opt.bounds.delta_theta_rad),
      opt.bounds.delta_footprint_px, ToString(opt.bounds.surface));
  rep.json["parameters"] = {
      {"seed", opt.seed},
      {"trials", opt.trials},
      {"wall_distance_in", opt.wall_distance_in},
      {"door_width_in", opt.door_width_in},
      {"door_offset_in", opt.door_offset_in},
      {"short_side_edges",
       opt.edges == ShortSideEdges::kPaperSensorRays ? "paper_sensor_rays" : "field_of_view_edges"},
      {"fov_deg", robot.camera.fov_deg},
      {"image_width_px", robot.camera.image_width_px},
      {"focal_length_mm", robot.camera.focal_length_mm},
      {"pixel_pitch_mm", robot.camera.pixel_pitch_mm},
      {"delta_theta_deg", RadToDeg(opt.bounds.delta_theta_rad)},
      {"delta_footprint_px", opt.bounds.delta_footprint_px},
      {"surface", ToString(opt.bounds.surface)}};
}

// Table 5.2: the approximation columns are geometry, computed; the returned-range columns
// are the paper's empirical summary, used as given.
void AddTable52(const CameraModel& cam, SensingReport& rep) {
  std::string& out = rep.text;
  out += "Table 5.2  Composite ranging error (%): paper | ours (approximation computed)\n";
  out += "  stare   L->RL         R->RR         dL->L  dR->R (paper's, used as given)\n";
  for (int i = 0; i < 3; ++i) {
    const double s = kStaresDeg[i];
    const CompositeRangeError ours = ApproximationFromGeometry(cam, DegToRad(s));
    out += fmt::format("  {:3.0f}   {:4.2f} | {:4.2f}   {:4.2f} | {:4.2f}   {:5.1f}  {:5.1f}\n", s,
                       kPaperTable52[i][0], ours.approx_l_pct, kPaperTable52[i][1],
                       ours.approx_r_pct, kPaperTable52[i][2], kPaperTable52[i][3]);
    rep.json["table_5_2"].push_back({{"stare_deg", s},
                                     {"paper_approx_l_pct", kPaperTable52[i][0]},
                                     {"ours_approx_l_pct", ours.approx_l_pct},
                                     {"paper_approx_r_pct", kPaperTable52[i][1]},
                                     {"ours_approx_r_pct", ours.approx_r_pct},
                                     {"returned_l_pct", kPaperTable52[i][2]},
                                     {"returned_r_pct", kPaperTable52[i][3]}});
  }
}

// Table 5.3.
void AddTable53(const CameraModel& cam, const ReportOptions& opt, SensingReport& rep) {
  std::string& out = rep.text;
  out += "\nTable 5.3  Worst-case width error, linear first-order model (in)\n";
  out +=
      "  geometry     stare  paper   ours: sum|d*D|  (diff)   |grad.D|  (diff)   terms "
      "d*D (in)\n";
  for (Geometry g : {Geometry::kTwoSide, Geometry::kShortSide}) {
    for (int i = 0; i < 3; ++i) {
      const double s = kStaresDeg[i];
      const LinearEstimate e =
          Must(LinearFirstOrder(cam, SceneAt(opt, s), g, opt.bounds, opt.edges), "Table 5.3");
      const double paper =
          g == Geometry::kTwoSide ? kPaperTable53TwoSide[i] : kPaperTable53ShortSide[i];
      std::string terms;
      for (const LinearTerm& t : e.terms) {
        terms += fmt::format(" {}={:+.2f}", t.input, t.contribution_in);
      }
      out += fmt::format("  {:<10}   {:3.0f}   {:5.2f}   {:13.2f}   {}   {:7.2f}  {}  {}\n",
                         ToString(g), s, paper, e.worst_case_in, Ratio(e.worst_case_in, paper),
                         e.dot_product_in, Ratio(e.dot_product_in, paper), terms);
      rep.json["table_5_3"].push_back({{"geometry", ToString(g)},
                                       {"stare_deg", s},
                                       {"paper_in", paper},
                                       {"ours_worst_case_in", e.worst_case_in},
                                       {"ours_dot_product_in", e.dot_product_in},
                                       {"width_error_free_in", e.width_in},
                                       {"terms", TermsJson(e)}});
    }
  }
}

// Table 5.4: Short Side with half the theta error (twice the sensors).
void AddTable54(const CameraModel& cam, const ReportOptions& opt, SensingReport& rep) {
  std::string& out = rep.text;
  out += "\nTable 5.4  Short Side worst-case error with dtheta = 3.75 deg (in)\n";
  out += "  stare  paper   ours sum|d*D|  (diff)   |grad.D|  (diff)\n";
  ErrorBounds half = opt.bounds;
  half.delta_theta_rad = opt.bounds.delta_theta_rad / 2.0;
  for (int i = 0; i < 3; ++i) {
    const double s = kStaresDeg[i];
    const LinearEstimate e = Must(
        LinearFirstOrder(cam, SceneAt(opt, s), Geometry::kShortSide, half, opt.edges), "Table 5.4");
    out += fmt::format("  {:3.0f}   {:5.2f}   {:13.2f}   {}   {:7.2f}  {}\n", s, kPaperTable54[i],
                       e.worst_case_in, Ratio(e.worst_case_in, kPaperTable54[i]), e.dot_product_in,
                       Ratio(e.dot_product_in, kPaperTable54[i]));
    rep.json["table_5_4"].push_back({{"stare_deg", s},
                                     {"paper_in", kPaperTable54[i]},
                                     {"ours_worst_case_in", e.worst_case_in},
                                     {"ours_dot_product_in", e.dot_product_in},
                                     {"terms", TermsJson(e)}});
  }
}

// Table 5.5: tolerance in theta for a 2 in worst case.
void AddTable55(const CameraModel& cam, const ReportOptions& opt, SensingReport& rep) {
  std::string& out = rep.text;
  out += "\nTable 5.5  Short Side dtheta tolerance for worst-case error within 2 in (deg)\n";
  out += "  stare  paper   ours   (search capped at 45 deg, where Tables 4.2/4.3 turn gross)\n";
  for (int i = 0; i < 3; ++i) {
    const double s = kStaresDeg[i];
    const double tol =
        RadToDeg(Must(ShortSideThetaTolerance(cam, SceneAt(opt, s), opt.bounds, 2.0), "Table 5.5"));
    out += fmt::format("  {:3.0f}   {:5.1f}   {:5.2f}\n", s, kPaperTable55Deg[i], tol);
    rep.json["table_5_5"].push_back(
        {{"stare_deg", s}, {"paper_deg", kPaperTable55Deg[i]}, {"ours_deg", tol}});
  }
}

// Table 5.6 and Figures 5.4-5.9: the Monte Carlo experiment, one generator for the run.
// Returns the Short Side RMS width error at 90 deg, relative to the door's width.
double AddTable56(const CameraModel& cam, const ReportOptions& opt, SensingReport& rep) {
  std::string& out = rep.text;
  std::mt19937_64 rng(opt.seed);
  MonteCarloConfig mc;
  mc.trials = opt.trials;
  mc.bounds = opt.bounds;
  mc.edges = opt.edges;
  out += fmt::format("\nTable 5.6  P(|width error| <= 2 in), Monte Carlo, {} trials per stare\n",
                     opt.trials);
  out += "  geometry     stare  paper   ours   (diff)   mean err  std dev  rejected\n";
  double short90_rms_rel = 0.0;
  for (Geometry g : {Geometry::kShortSide, Geometry::kTwoSide}) {
    for (int i = 0; i < 3; ++i) {
      const double s = kStaresDeg[i];
      const MonteCarloResult r = Must(RunMonteCarlo(cam, SceneAt(opt, s), g, mc, rng), "Table 5.6");
      const bool has_paper = g == Geometry::kShortSide;
      out += fmt::format(
          "  {:<10}   {:3.0f}   {}   {:5.3f}   {}   {:+8.2f}  {:7.2f}  {:8d}\n", ToString(g), s,
          has_paper ? fmt::format("{:5.2f}", kPaperTable56[i]) : "    -", r.p_within_tolerance,
          has_paper ? Ratio(r.p_within_tolerance, kPaperTable56[i]) : "    -", r.mean_error_in,
          r.stddev_in, r.rejected);
      nlohmann::json row = {{"geometry", ToString(g)},
                            {"stare_deg", s},
                            {"ours_p_within_2in", r.p_within_tolerance},
                            {"mean_error_in", r.mean_error_in},
                            {"stddev_in", r.stddev_in},
                            {"trials", r.trials},
                            {"rejected", r.rejected}};
      if (has_paper) row["paper_p_within_2in"] = kPaperTable56[i];
      rep.json["table_5_6"].push_back(row);
      if (g == Geometry::kShortSide && s == 90.0) {
        short90_rms_rel = std::sqrt(r.mean_error_in * r.mean_error_in + r.stddev_in * r.stddev_in) /
                          opt.door_width_in;
      }
      rep.figures.emplace_back(
          FigureName(g, s),
          plot::HistogramOf(r.errors_in, -12.0, 12.0, 48,
                            fmt::format("{} Geometry, stare {:.0f} deg ({} trials, seed {})",
                                        ToString(g), s, r.trials, opt.seed),
                            "width error (in)"));
    }
  }
  return short90_rms_rel;
}

// Table 4.1 and the Bayes derivation (door30 included). The class-conditional spread is
// fitted to Table 4.1's interior boundaries (the paper's boundaries encode its measured
// error); our own Monte Carlo spread at 90 deg is printed beside it for comparison.
void AddTable41(double short90_rms_rel, SensingReport& rep) {
  std::string& out = rep.text;
  nlohmann::json& js = rep.json;
  BayesModel bayes;
  const double fitted = FitSigmaToTable41(bayes);
  bayes.sigma_rel = fitted;
  const auto derived = DeriveBayesBoundaries(bayes);
  out += fmt::format(
      "\nTable 4.1  Class boundaries (in): paper | Bayes-derived\n"
      "  model: normal width error, sigma = {:.2f} % of width (fitted to Table 4.1's 33.5 and "
      "38.8 in; our Short Side RMS error at 90 deg is {:.2f} %), priors Table 6.8 (30:22 "
      "32:4 36:412 40:22, doubles 4), clutter 15.91 % (Table 6.10) uniform on 12..96 in\n",
      100.0 * fitted, 100.0 * short90_rms_rel);
  out += "  class   paper low  high   derived low  high\n";
  const auto paper41 = Table41Boundaries();
  for (const ClassBoundary& d : derived) {
    std::string paper = "     -      -";
    for (const ClassBoundary& p : paper41) {
      if (p.door_class == d.door_class) paper = fmt::format("{:6.1f} {:6.1f}", p.low_in, p.high_in);
    }
    out += fmt::format("  {:<6}  {}   {:9.2f} {:5.2f}\n", ToString(d.door_class), paper, d.low_in,
                       d.high_in);
    js["table_4_1"].push_back({{"class", ToString(d.door_class)},
                               {"derived_low_in", d.low_in},
                               {"derived_high_in", d.high_in}});
  }
  for (const ClassBoundary& p : paper41) {
    bool found = false;
    for (const ClassBoundary& d : derived) found = found || d.door_class == p.door_class;
    if (!found) {
      out += fmt::format(
          "  {:<6}  {:6.1f} {:6.1f}         (never the Bayes decision with these "
          "priors)\n",
          ToString(p.door_class), p.low_in, p.high_in);
    }
  }
  js["bayes_sigma_rel_fitted"] = fitted;
  js["short_side_90_rms_rel"] = short90_rms_rel;
  out += "  in use (DefaultBoundaries):";
  for (const ClassBoundary& b : DefaultBoundaries()) {
    out += fmt::format(" {} [{:.1f}, {:.1f})", ToString(b.door_class), b.low_in, b.high_in);
  }
  out += "\n";
}

}  // namespace

SensingReport BuildSensingReport(const RobotConfig& robot, const ReportOptions& opt) {
  const CameraModel cam = CameraModel::FromConfig(robot.camera);
  SensingReport rep;
  AddParameters(robot, opt, rep);
  AddTable52(cam, rep);
  AddTable53(cam, opt, rep);
  AddTable54(cam, opt, rep);
  AddTable55(cam, opt, rep);
  const double short90_rms_rel = AddTable56(cam, opt, rep);
  AddTable41(short90_rms_rel, rep);
  return rep;
}

void WriteReportFigures(const SensingReport& report, const std::string& dir) {
  std::filesystem::create_directories(dir);
  for (const auto& [name, chart] : report.figures) {
    plot::WriteBarChartPng(chart, (std::filesystem::path(dir) / (name + ".png")).string());
  }
}

}  // namespace stickrep::sensing
