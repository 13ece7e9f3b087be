#include "sweep_results.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>

#include <nlohmann/json.hpp>

#include "climbsim/errors.hpp"
#include "plot/line_chart.hpp"
#include "plot/trace_table.hpp"

namespace climbsim::sweep {
namespace {

std::string num(double v) {
  char text[40];
  std::snprintf(text, sizeof(text), "%.17g", v);
  return text;
}

/// A CSV cell: quoted when it holds a comma, a quote or a newline.
std::string cell(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string out = "\"";
  for (const char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

/// The values of the swept keys (those with more than one value; all if none has).
std::string legend(const std::vector<SweepAxis>& axes, const Variant& v) {
  const bool any_swept = std::any_of(axes.begin(), axes.end(), [](const SweepAxis& a) { return a.values.size() > 1; });
  std::string out;
  for (std::size_t a = 0; a < axes.size() && a < v.values.size(); ++a) {
    if (any_swept && axes[a].values.size() < 2) continue;
    out += (out.empty() ? "" : ", ") + axes[a].key + "=" + v.values[a];
  }
  return out;
}

double numberOr(const nlohmann::json& summary, const char* key, double fallback) {
  const auto it = summary.find(key);
  return it != summary.end() && it->is_number() ? it->get<double>() : fallback;
}

std::string textOf(const nlohmann::json& summary, const char* key) {
  const auto it = summary.find(key);
  return it != summary.end() && it->is_string() ? it->get<std::string>() : std::string();
}

/// A time of summary.json: a number, or an object's first_at_s (seal_over_nothing); none for null.
std::optional<double> timeOf(const nlohmann::json& summary, const char* key) {
  const auto it = summary.find(key);
  if (it == summary.end()) return std::nullopt;
  if (it->is_number()) return it->get<double>();
  if (it->is_object() && it->contains("first_at_s") && it->at("first_at_s").is_number()) {
    return it->at("first_at_s").get<double>();
  }
  return std::nullopt;
}

std::string optionalNum(const std::optional<double>& v) { return v ? num(*v) : std::string(); }

}  // namespace

VariantResult readVariant(const Variant& variant, const std::string& run_dir, double wall_s, double from_s) {
  namespace fs = std::filesystem;
  VariantResult r;
  r.variant = variant;
  r.wall_s = wall_s;
  const std::string summary_path = (fs::path(run_dir) / "summary.json").string();
  std::ifstream in(summary_path);
  const auto summary = nlohmann::json::parse(in, nullptr, false);
  if (!in || summary.is_discarded() || !summary.is_object()) throw ConfigError(summary_path + ": no summary");
  r.outcome = summary.value("outcome", std::string("failed"));
  r.fell = summary.value("fell", false);
  r.max_slip_mps = summary.value("max_slip_mps", 0.0);
  r.slid = summary.value("slid", false);
  r.slide_m = numberOr(summary, "slide_m", 0.0);
  r.slide_limit_m = numberOr(summary, "slide_limit_m", 0.0);
  r.adhesion_failed = summary.value("adhesion_failed", r.fell || r.slid);
  r.fell_at_s = timeOf(summary, "fell_at_s");
  r.seal_over_nothing_at_s = timeOf(summary, "seal_over_nothing");
  r.wheels_over_nothing_at_s = timeOf(summary, "wheels_over_nothing");
  r.dropped_samples = static_cast<long long>(numberOr(summary, "dropped_samples", 0.0));
  r.exit_code = static_cast<int>(numberOr(summary, "exit_code", 0.0));
  r.culprit = textOf(summary, "culprit");
  r.reason = textOf(summary, "reason");
  const auto trace = plot::TraceTable::read((fs::path(run_dir) / "trace.csv").string());
  r.t_s = trace.column("t_s");
  r.downforce_n = trace.column("downforce_n");
  r.pf_x_m = trace.column("pf_x_m");
  r.pf_y_m = trace.column("pf_y_m");
  double sum = 0.0;
  std::size_t n = 0;
  r.min_downforce_n = std::nan("");
  for (std::size_t k = 1; k < trace.rows(); ++k) {
    if (r.t_s[k] < from_s) continue;
    const double f = r.downforce_n[k];
    sum += f;
    ++n;
    r.min_downforce_n = n == 1 ? f : std::min(r.min_downforce_n, f);
    r.max_pf_shift_m = std::max(r.max_pf_shift_m, std::hypot(r.pf_x_m[k], r.pf_y_m[k]));
  }
  r.mean_downforce_n = n > 0 ? sum / static_cast<double>(n) : std::nan("");
  return r;
}

std::string sweepCsv(const std::vector<SweepAxis>& axes, const std::vector<VariantResult>& results) {
  std::string out = "variant";
  for (const auto& axis : axes) out += "," + cell(axis.key);
  out += ",outcome,fell,min_downforce_n,mean_downforce_n,max_pf_shift_m,max_slip_mps,wall_s,dir";
  out += ",slid,slide_m,slide_limit_m,adhesion_failed,fell_at_s,seal_over_nothing_at_s,wheels_over_nothing_at_s"
         ",dropped_samples,exit_code,culprit,reason\n";
  const auto flag = [](bool b) { return std::string(b ? "true" : "false"); };
  for (const auto& r : results) {
    out += std::to_string(r.variant.index);
    for (const auto& value : r.variant.values) out += "," + cell(value);
    out += "," + r.outcome + "," + flag(r.fell) + "," + num(r.min_downforce_n) + "," + num(r.mean_downforce_n) + "," +
           num(r.max_pf_shift_m) + "," + num(r.max_slip_mps) + "," + num(r.wall_s) + "," + cell(r.variant.name);
    out += "," + flag(r.slid) + "," + num(r.slide_m) + "," + num(r.slide_limit_m) + "," + flag(r.adhesion_failed) +
           "," + optionalNum(r.fell_at_s) + "," + optionalNum(r.seal_over_nothing_at_s) + "," +
           optionalNum(r.wheels_over_nothing_at_s) + "," + std::to_string(r.dropped_samples) + "," +
           std::to_string(r.exit_code) + "," + cell(r.culprit) + "," + cell(r.reason) + "\n";
  }
  return out;
}

std::string outcomeMark(const VariantResult& r) {
  if (r.fell) return " (fell)";
  if (r.outcome == "failed" || r.outcome == "stopped") return " (" + r.outcome + ")";
  if (r.slid) return " (slid)";
  return "";
}

namespace {
/// The overlay of `results`: a panel per quantity, a series per variant.
cv::Mat overlay(const std::vector<SweepAxis>& axes, const std::vector<VariantResult>& results,
                const std::string& title, const std::vector<std::string>& y_labels,
                const std::vector<std::function<std::vector<double>(const VariantResult&)>>& values) {
  plot::ChartSpec spec;
  spec.title = title;
  for (std::size_t p = 0; p < y_labels.size(); ++p) {
    plot::Panel panel{y_labels[p], {}, 0};
    for (std::size_t i = 0; i < results.size(); ++i) {
      const auto& r = results[i];
      panel.series.push_back({legend(axes, r.variant) + outcomeMark(r), r.t_s, values[p](r),
                              plot::paletteColour(static_cast<int>(i)), false});
    }
    spec.panels.push_back(std::move(panel));
  }
  return plot::drawChart(spec);
}

std::vector<double> millimetres(const std::vector<double>& m) {
  std::vector<double> mm(m.size());
  std::transform(m.begin(), m.end(), mm.begin(), [](double v) { return v * 1e3; });
  return mm;
}
}  // namespace

cv::Mat downforceOverlay(const std::vector<SweepAxis>& axes, const std::vector<VariantResult>& results) {
  return overlay(axes, results, "Sweep: downforce of every variant", {"F [N]"},
                 {[](const VariantResult& r) { return r.downforce_n; }});
}

cv::Mat pfOverlay(const std::vector<SweepAxis>& axes, const std::vector<VariantResult>& results) {
  return overlay(axes, results, "Sweep: point of action P_F of every variant (robot frame)",
                 {"P_F x [mm]", "P_F y [mm]"},
                 {[](const VariantResult& r) { return millimetres(r.pf_x_m); },
                  [](const VariantResult& r) { return millimetres(r.pf_y_m); }});
}

}  // namespace climbsim::sweep
