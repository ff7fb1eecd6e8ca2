// The GI benchmark's JSON document and Markdown report. The JSON keys are an interface:
// scripts/h100-run collects the document, lghd serves it (GET /v1/benchmark/result), and
// docs/BENCHMARKS.md quotes it.
#include <cmath>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "lgh/bench/gi_benchmark.hpp"
#include "lgh/enum_names.hpp"

namespace lgh::bench {
namespace {

using json = nlohmann::json;

// The paper's figures (RTX 2080, 1280x720; Lin & Yuksel 2019, Tables 2 and 3).
struct PaperTable2 {
  int vpls;
  double generation;
  double construction;
  double noShadow;
  double oneShadow;
  double fourShadows;
};
constexpr PaperTable2 kPaperTable2[] = {{1000, 0.1, 7.0, 5.6, 10.1, 15.5},
                                        {10000, 0.2, 9.2, 8.1, 14.3, 22.4},
                                        {100000, 0.4, 12.1, 11.2, 18.4, 28.5},
                                        {1000000, 2.5, 32.0, 16.0, 24.3, 37.0}};
struct PaperTable3 {
  const char* interleave;
  double gbuffer;
  double lighting;
  double shadowRays;
  double shadowFilter;
  double compositing;
  double total;
};
constexpr PaperTable3 kPaperTable3[] = {{"none", 1.1, 24.8, 2.3, 1.9, 0.1, 30.2},
                                        {"2x2", 1.1, 9.0, 2.2, 2.8, 0.1, 15.2},
                                        {"4x4", 1.0, 3.8, 2.2, 2.9, 0.1, 10.1}};

json number(double value) { return std::isfinite(value) ? json(value) : json("inf"); }

json timings(const std::vector<TimingStats>& passes) {
  json array = json::array();
  for (const TimingStats& pass : passes) {
    array.push_back({{"name", pass.name},
                     {"median_ms", pass.medianMs},
                     {"min_ms", pass.minMs},
                     {"max_ms", pass.maxMs}});
  }
  return array;
}

json overdrawJson(const OverdrawStats& stats) {
  json histogram = json::array();
  for (const OverdrawStats::Bin& bin : stats.histogram) {
    histogram.push_back({{"from", bin.from}, {"to", bin.to}, {"pixels", bin.pixels}});
  }
  return {{"pixels", stats.pixels}, {"mean", stats.mean}, {"max", stats.max},
          {"p50", stats.p50},       {"p95", stats.p95},   {"histogram", histogram}};
}

json errorJson(const GiError& e) {
  return {{"relative_rmse", e.relativeRmse},
          {"psnr", number(e.psnr)},
          {"diffuse_relative_rmse", e.diffuseRelativeRmse},
          {"glossy_relative_rmse", e.glossyRelativeRmse},
          {"bias", e.bias},
          {"diffuse_bias", e.diffuseBias},
          {"glossy_bias", e.glossyBias},
          {"glossy_fraction", e.glossyFraction}};
}

json settingsJson(const GiBenchmarkResult& result) {
  const GiBenchmarkOptions& o = result.options;
  json interleaves = json::array();
  for (InterleaveMode mode : o.interleaves) interleaves.push_back(std::string(enumName(mode)));
  return {{"scene", o.sceneName},
          {"scene_triangles", result.sceneTriangles},
          {"width", o.width},
          {"height", o.height},
          {"vpls", o.vplCounts},
          {"bounces", o.bounces},
          {"alpha", o.alpha},
          {"alpha_paper", o.alpha / 2.0F},
          {"path", std::string(enumName(o.path))},
          {"shadow_jitter", o.shadowJitter},
          {"depth_prepass", o.depthPrepass},
          {"table3_vpls", o.table3Vpls},
          {"interleaves", interleaves},
          {"warmup_iterations", o.warmupIterations},
          {"timed_iterations", o.timedIterations},
          {"overdraw", o.overdraw},
          {"quality", o.quality},
          {"quality_width", o.qualityWidth},
          {"quality_height", o.qualityHeight},
          {"quality_vpls", o.qualityVpls},
          {"quality_alphas", o.qualityAlphas},
          {"path_traced_samples", o.pathTracedSamples},
          {"seed", o.seed}};
}

std::string ms(double value) { return value > 0.0 ? fmt::format("{:.3f}", value) : "-"; }

std::string countLabel(int count) {
  if (count >= 1000000 && count % 1000000 == 0) return fmt::format("{}M", count / 1000000);
  if (count >= 1000 && count % 1000 == 0) return fmt::format("{}K", count / 1000);
  return std::to_string(count);
}

const PaperTable2* paperRow(int vpls) {
  for (const PaperTable2& row : kPaperTable2) {
    if (row.vpls == vpls) return &row;
  }
  return nullptr;
}

std::string table2Markdown(const GiBenchmarkResult& result) {
  std::string header = "| | ";
  std::string rule = "|---|";
  for (const GiTable2Row& row : result.table2) {
    header += countLabel(row.vpls) + " | ";
    rule += "---|";
  }
  std::string out = header + "\n" + rule + "\n";
  const auto line = [&](const std::string& name, auto&& cell) {
    out += "| " + name + " |";
    for (const GiTable2Row& row : result.table2) out += " " + cell(row) + " |";
    out += "\n";
  };
  const auto paper = [&](auto member) {
    return [member](const GiTable2Row& row) {
      const PaperTable2* p = paperRow(row.vpls);
      return p != nullptr ? fmt::format("{}", p->*member) : std::string("-");
    };
  };
  line("levels / grid lights",
       [](const GiTable2Row& r) { return fmt::format("{} / {}", r.levels, r.gridLights); });
  line("lit VPLs", [](const GiTable2Row& r) { return std::to_string(r.litVpls); });
  line("VPL generation", [](const GiTable2Row& r) { return ms(r.generationMs); });
  line("paper: VPL generation", paper(&PaperTable2::generation));
  line("construction", [](const GiTable2Row& r) { return ms(r.constructionMs); });
  line("paper: construction", paper(&PaperTable2::construction));
  line("render, no shadow", [](const GiTable2Row& r) { return ms(r.renderNoShadowMs); });
  line("paper: render, no shadow", paper(&PaperTable2::noShadow));
  line("render, 1 shadow/pixel", [](const GiTable2Row& r) { return ms(r.render1ShadowMs); });
  line("paper: render, 1 shadow/pixel", paper(&PaperTable2::oneShadow));
  line("render, 4 shadows/pixel", [](const GiTable2Row& r) { return ms(r.render4ShadowsMs); });
  line("paper: render, 4 shadows/pixel", paper(&PaperTable2::fourShadows));
  line("whole frame, 4 shadows/pixel", [](const GiTable2Row& r) { return ms(r.frame4ShadowsMs); });
  line("lights per pixel: mean / p95 / max", [](const GiTable2Row& r) {
    return r.overdraw && r.overdraw->pixels > 0
               ? fmt::format("{:.1f} / {} / {}", r.overdraw->mean, r.overdraw->p95, r.overdraw->max)
               : std::string("-");
  });
  return out;
}

std::string table3Markdown(const GiBenchmarkResult& result) {
  std::string out = "| | ";
  std::string rule = "|---|";
  for (const GiTable3Column& c : result.table3) {
    out += fmt::format("{} | paper {} | ", enumName(c.interleave), enumName(c.interleave));
    rule += "---|---|";
  }
  out += "\n" + rule + "\n";
  const auto paperOf = [](InterleaveMode mode) -> const PaperTable3* {
    for (const PaperTable3& p : kPaperTable3) {
      if (enumName(mode) == p.interleave) return &p;
    }
    return nullptr;
  };
  const auto line = [&](const std::string& name, auto&& ours, auto&& theirs) {
    out += "| " + name + " |";
    for (const GiTable3Column& c : result.table3) {
      const PaperTable3* p = paperOf(c.interleave);
      out += " " + ours(c) + " | " + (p != nullptr ? theirs(*p) : std::string("-")) + " |";
    }
    out += "\n";
  };
  const auto none = [](const PaperTable3&) { return std::string("-"); };
  line(
      "G-buffer", [](const GiTable3Column& c) { return ms(c.gbufferMs); },
      [](const PaperTable3& p) { return fmt::format("{}", p.gbuffer); });
  line(
      "VPL generation", [](const GiTable3Column& c) { return ms(c.generationMs); },
      [](const PaperTable3&) { return std::string("(0.4)"); });
  line(
      "LGH construction", [](const GiTable3Column& c) { return ms(c.constructionMs); },
      [](const PaperTable3&) { return std::string("(12.1)"); });
  line(
      "lighting computation", [](const GiTable3Column& c) { return ms(c.lightingMs); },
      [](const PaperTable3& p) { return fmt::format("{}", p.lighting); });
  line(
      "shadow ray tracing (setup + rays)",
      [](const GiTable3Column& c) { return ms(c.shadowRaysMs); },
      [](const PaperTable3& p) { return fmt::format("{}", p.shadowRays); });
  line(
      "shadow filtering", [](const GiTable3Column& c) { return ms(c.shadowFilterMs); },
      [](const PaperTable3& p) { return fmt::format("{}", p.shadowFilter); });
  line(
      "compositing (direct + composite)",
      [](const GiTable3Column& c) { return ms(c.compositingMs); },
      [](const PaperTable3& p) { return fmt::format("{}", p.compositing); });
  line(
      "render (the paper's total)", [](const GiTable3Column& c) { return ms(c.renderMs); },
      [](const PaperTable3& p) { return fmt::format("{}", p.total); });
  line(
      "**whole frame** (with generation and construction)",
      [](const GiTable3Column& c) { return "**" + ms(c.frameMs) + "**"; },
      [](const PaperTable3& p) { return fmt::format("{:.1f}", p.total + 0.4 + 12.1); });
  line(
      "target",
      [](const GiTable3Column& c) {
        if (c.targetMs <= 0.0) return std::string("-");
        return fmt::format("<= {:.0f}: {}", c.targetMs,
                           c.frameMs <= c.targetMs ? "met" : "not met");
      },
      none);
  return out;
}

// The question: which settings keep the frame's relative RMSE against the brute force
// over the same VPLs under 5%.
constexpr double kQualityTarget = 0.05;

bool underQualityTarget(const GiQualityRun& run) {
  return run.vsVplReference.relativeRmse < kQualityTarget;
}

std::string errorCells(const GiError& e) {
  return fmt::format("{:.3f} / {:.3f} / {:.3f} / {:+.1f}%", e.relativeRmse, e.diffuseRelativeRmse,
                     e.glossyRelativeRmse, 100.0 * e.bias);
}

std::string qualityMarkdown(const GiQuality& q) {
  std::string out = fmt::format(
      "{}x{}, {} VPLs, path tracer {} samples per pixel, shadowed brute force {:.1f} ms. Cells: "
      "relative RMSE all / diffuse / glossy pixels, and the bias (summed luminance, > 0 too "
      "bright). The VPLs themselves (shadowed brute force, no clamp) against the path tracer: "
      "{}.\n\n",
      q.width, q.height, q.vpls, q.pathTracedSamples, q.bruteForceMs,
      errorCells(q.vplsVsPathTracer));
  out +=
      "| alpha (paper) | interleave | frame vs VPLs (shadowed, no clamp) | frame vs path tracer | "
      "hierarchy alone (LGH clamp) | hierarchy + clamp |\n|---|---|---|---|---|---|\n";
  std::vector<std::string> underTarget;
  for (const GiQualityRun& r : q.runs) {
    out += fmt::format("| {} ({}) | {} | {} | {} | {} | {} |\n", r.alpha, r.alpha / 2.0F,
                       enumName(r.interleave), errorCells(r.vsVplReference),
                       errorCells(r.vsPathTracer), errorCells(r.hierarchyOnly),
                       errorCells(r.hierarchyAndClamp));
    if (underQualityTarget(r)) {
      underTarget.push_back(fmt::format("alpha {} {}", r.alpha, enumName(r.interleave)));
    }
  }
  out += fmt::format(
      "\nUnder {:.0f}% relative RMSE against the brute force over the VPLs (shadowed, no clamp): "
      "{}.\n",
      100.0 * kQualityTarget,
      underTarget.empty() ? "none" : fmt::format("{}", fmt::join(underTarget, ", ")));
  return out;
}

}  // namespace

nlohmann::json giBenchmarkJson(const GiBenchmarkResult& result) {
  json table2 = json::array();
  for (const GiTable2Row& row : result.table2) {
    json entry = {{"vpls", row.vpls},
                  {"levels", row.levels},
                  {"grid_lights", row.gridLights},
                  {"lit_vpls", row.litVpls},
                  {"generation_ms", row.generationMs},
                  {"construction_ms", row.constructionMs},
                  {"render_no_shadow_ms", row.renderNoShadowMs},
                  {"render_1_shadow_ms", row.render1ShadowMs},
                  {"render_4_shadows_ms", row.render4ShadowsMs},
                  {"frame_4_shadows_ms", row.frame4ShadowsMs},
                  {"passes_4_shadows", timings(row.passes)}};
    if (row.overdraw) entry["overdraw"] = overdrawJson(*row.overdraw);
    if (const PaperTable2* paper = paperRow(row.vpls)) {
      entry["paper"] = {{"generation_ms", paper->generation},
                        {"construction_ms", paper->construction},
                        {"render_no_shadow_ms", paper->noShadow},
                        {"render_1_shadow_ms", paper->oneShadow},
                        {"render_4_shadows_ms", paper->fourShadows}};
    }
    table2.push_back(std::move(entry));
  }
  json table3 = json::array();
  for (const GiTable3Column& c : result.table3) {
    json entry = {{"interleave", std::string(enumName(c.interleave))},
                  {"passes", timings(c.passes)},
                  {"gbuffer_ms", c.gbufferMs},
                  {"generation_ms", c.generationMs},
                  {"construction_ms", c.constructionMs},
                  {"lighting_ms", c.lightingMs},
                  {"shadow_rays_ms", c.shadowRaysMs},
                  {"shadow_filter_ms", c.shadowFilterMs},
                  {"compositing_ms", c.compositingMs},
                  {"render_ms", c.renderMs},
                  {"frame_ms", c.frameMs}};
    if (c.targetMs > 0.0) {
      entry["target_ms"] = c.targetMs;
      entry["meets_target"] = c.frameMs <= c.targetMs;
    }
    table3.push_back(std::move(entry));
  }
  json document = {{"benchmark", "lgh-gi"},
                   {"device", result.device.toJson()},
                   {"shadows", result.shadows.toJson()},
                   {"settings", settingsJson(result)},
                   {"table2", table2},
                   {"table3", table3},
                   {"scaling",
                    {{"render_ratio_largest_over_10k", result.scalingRatio},
                     {"target", 2.0},
                     {"paper", 37.0 / 22.4}}}};
  if (result.quality) {
    const GiQuality& q = *result.quality;
    json runs = json::array();
    for (const GiQualityRun& r : q.runs) {
      runs.push_back({{"alpha", r.alpha},
                      {"alpha_paper", r.alpha / 2.0F},
                      {"interleave", std::string(enumName(r.interleave))},
                      {"vs_vpl_reference", errorJson(r.vsVplReference)},
                      {"vs_path_tracer", errorJson(r.vsPathTracer)},
                      {"hierarchy_only", errorJson(r.hierarchyOnly)},
                      {"hierarchy_and_clamp", errorJson(r.hierarchyAndClamp)},
                      {"under_5_percent_vs_vpl_reference", underQualityTarget(r)}});
    }
    document["quality"] = {{"width", q.width},
                           {"height", q.height},
                           {"vpls", q.vpls},
                           {"path_traced_samples", q.pathTracedSamples},
                           {"reference_clamp", "none"},
                           {"bruteforce_ms", q.bruteForceMs},
                           {"vpls_vs_path_tracer", errorJson(q.vplsVsPathTracer)},
                           {"runs", runs}};
  }
  return document;
}

std::string giBenchmarkMarkdown(const GiBenchmarkResult& result) {
  const GiBenchmarkOptions& o = result.options;
  std::string out = fmt::format(
      "# lgh-bench gi\n\n{} ({}), Vulkan: {}; scene {} ({} triangles), {}x{}, {} bounces, alpha "
      "{} (the paper's {}), lighting path {}{}, medians of {} frames (GPU ms).\n\n",
      result.device.glRenderer, result.device.contextPath, result.shadows.deviceName, o.sceneName,
      result.sceneTriangles, o.width, o.height, o.bounces, o.alpha, o.alpha / 2.0F,
      enumName(o.path), o.depthPrepass ? ", depth pre-pass" : "", o.timedIterations);
  out += "## Table 2\n\n" + table2Markdown(result);
  if (result.scalingRatio > 0.0) {
    out += fmt::format(
        "\nRender time (4 shadows/pixel), largest VPL count over 10K: {:.2f}x (target <= 2x; "
        "paper 1.65x).\n",
        result.scalingRatio);
  }
  out += fmt::format("\n## Table 3 ({} VPLs, 4 shadow samples per pixel)\n\n", o.table3Vpls) +
         table3Markdown(result);
  if (result.quality) out += "\n## Quality\n\n" + qualityMarkdown(*result.quality);
  out +=
      "\n## Fig. 5\n\n![frames and overdraw](gi_heatmaps.png)\n\n![overdraw against grid "
      "lights](gi_overdraw_plot.png)\n";
  return out;
}

}  // namespace lgh::bench
