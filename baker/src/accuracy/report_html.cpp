// report.html of `iblbake accuracy`: per stage, a hand-written SVG plot of error against time (both log
// scales), the Pareto front drawn as a line, the presets marked and named, and the measurements as a table.
// No scripts: the page is static.
#include "iblbake/accuracy/accuracy.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace ibl {

namespace {

std::string escape(const std::string& text) {
    std::string out;
    for (char c : text)
        out += c == '<'   ? "&lt;"
               : c == '>' ? "&gt;"
               : c == '&' ? "&amp;"
               : c == '"' ? "&quot;"
                          : std::string(1, c);
    return out;
}

std::string number(const char* pattern, double value) {
    char text[48];
    std::snprintf(text, sizeof text, pattern, value);
    return text;
}

// A decade axis covering [lo, hi] (both > 0).
struct LogAxis {
    double lo, hi;
    double position(double v, double from, double to) const {
        double t = (std::log10(std::max(v, lo)) - std::log10(lo)) / (std::log10(hi) - std::log10(lo));
        return from + t * (to - from);
    }
};

LogAxis axisFor(double lo, double hi) {
    lo = std::pow(10.0, std::floor(std::log10(lo)));
    hi = std::pow(10.0, std::ceil(std::log10(hi)));
    if (hi <= lo) hi = lo * 10.0;
    return {lo, hi};
}

constexpr double kWidth = 640, kHeight = 400, kLeft = 70, kRight = 20, kTop = 20, kBottom = 50;

std::string plot(const AccuracyStage& stage) {
    // Errors of exactly 0 (possible for a setting equal to its reference) sit on the axis floor.
    double tMin = 1e300, tMax = 0, eMin = 1e300, eMax = 0;
    for (const MeasuredSetting& s : stage.settings) {
        tMin = std::min(tMin, std::max(s.timeMs, 1e-3));
        tMax = std::max(tMax, std::max(s.timeMs, 1e-3));
        if (s.error > 0) eMin = std::min(eMin, s.error);
        eMax = std::max(eMax, s.error);
    }
    if (eMax <= 0) eMin = eMax = 1e-6;
    const LogAxis x = axisFor(tMin, tMax), y = axisFor(eMin, eMax);
    auto px = [&](double t) { return x.position(t, kLeft, kWidth - kRight); };
    auto py = [&](double e) { return y.position(e, kHeight - kBottom, kTop); };
    std::ostringstream svg;
    svg << "<svg class=\"plot\" data-stage=\"" << stage.name
        << "\" xmlns=\"http://www.w3.org/2000/svg\" width=\"" << kWidth << "\" height=\"" << kHeight
        << "\" viewBox=\"0 0 " << kWidth << " " << kHeight << "\">\n"
        << "<rect x=\"0\" y=\"0\" width=\"" << kWidth << "\" height=\"" << kHeight << "\" fill=\"#fff\"/>\n";
    for (double t = x.lo; t <= x.hi * 1.001; t *= 10) {
        double p = px(t);
        svg << "<line x1=\"" << p << "\" y1=\"" << kTop << "\" x2=\"" << p << "\" y2=\"" << kHeight - kBottom
            << "\" stroke=\"#ddd\"/><text x=\"" << p << "\" y=\"" << kHeight - kBottom + 16
            << "\" font-size=\"11\" text-anchor=\"middle\">" << number("%g", t) << "</text>\n";
    }
    for (double e = y.lo; e <= y.hi * 1.001; e *= 10) {
        double p = py(e);
        svg << "<line x1=\"" << kLeft << "\" y1=\"" << p << "\" x2=\"" << kWidth - kRight << "\" y2=\"" << p
            << "\" stroke=\"#ddd\"/><text x=\"" << kLeft - 6 << "\" y=\"" << p + 4
            << "\" font-size=\"11\" text-anchor=\"end\">" << number("%g%%", 100 * e) << "</text>\n";
    }
    svg << "<rect x=\"" << kLeft << "\" y=\"" << kTop << "\" width=\"" << kWidth - kLeft - kRight
        << "\" height=\"" << kHeight - kTop - kBottom << "\" fill=\"none\" stroke=\"#444\"/>\n"
        << "<text x=\"" << (kLeft + kWidth - kRight) / 2 << "\" y=\"" << kHeight - 12
        << "\" font-size=\"12\" text-anchor=\"middle\">time, ms (median; log scale)</text>\n"
        << "<text x=\"16\" y=\"" << (kTop + kHeight - kBottom) / 2
        << "\" font-size=\"12\" text-anchor=\"middle\" "
        << "transform=\"rotate(-90 16 " << (kTop + kHeight - kBottom) / 2
        << ")\">error vs reference (log scale)</text>\n";

    std::vector<const MeasuredSetting*> front;
    for (const MeasuredSetting& s : stage.settings)
        if (s.pareto) front.push_back(&s);
    std::sort(front.begin(), front.end(), [](auto* a, auto* b) { return a->timeMs < b->timeMs; });
    svg << "<polyline class=\"pareto-front\" fill=\"none\" stroke=\"#e07000\" stroke-width=\"2\" points=\"";
    for (const MeasuredSetting* s : front)
        svg << px(s->timeMs) << "," << py(s->error) << " ";
    svg << "\"/>\n";
    for (const MeasuredSetting& s : stage.settings)
        svg << "<circle cx=\"" << px(s.timeMs) << "\" cy=\"" << py(s.error) << "\" r=\""
            << (s.pareto ? 4.5 : 3.5) << "\" fill=\"" << (s.pareto ? "#e07000" : "#4a78b0")
            << "\" fill-opacity=\"0.8\"><title>" << escape(s.label) << ": " << number("%.3g ms", s.timeMs)
            << ", " << number("%.4g%%", 100 * s.error) << "</title></circle>\n";
    for (const MeasuredSetting& s : stage.settings) {
        if (s.preset.empty()) continue;
        double cx = px(s.timeMs), cy = py(s.error);
        svg << "<g class=\"preset-marker\" data-preset=\"" << s.preset << "\"><rect x=\"" << cx - 6
            << "\" y=\"" << cy - 6
            << "\" width=\"12\" height=\"12\" fill=\"none\" stroke=\"#c00\" stroke-width=\"2\"/>"
            << "<text x=\"" << cx + 9 << "\" y=\"" << cy - 8 << "\" font-size=\"12\" fill=\"#c00\">"
            << s.preset << "</text></g>\n";
    }
    svg << "</svg>\n";
    return svg.str();
}

std::string table(const AccuracyStage& stage) {
    std::ostringstream html;
    html << "<table><tr><th>setting</th><th>time (median)</th><th>error</th><th>max error</th><th>energy "
            "error</th><th>per part</th><th></th></tr>\n";
    for (const MeasuredSetting& s : stage.settings) {
        html << "<tr" << (s.preset.empty() ? "" : " class=\"preset\"") << "><td>" << escape(s.label)
             << "</td><td>" << number("%.3g ms", s.timeMs) << "</td><td>" << number("%.4g%%", 100 * s.error)
             << "</td><td>"
             << number(stage.name == "dfg" ? "%.3g" : "%.4g%%",
                       stage.name == "dfg" ? s.maxError : 100 * s.maxError)
             << "</td><td>" << number("%.3g%%", 100 * s.energyError) << "</td><td>";
        for (const auto& [part, error] : s.partErrors)
            html << escape(part) << " " << number("%.3g%%", 100 * error) << "; ";
        html << "</td><td>" << (s.preset.empty() ? "" : s.preset) << (s.pareto ? " pareto" : "")
             << "</td></tr>\n";
    }
    html << "</table>\n";
    return html.str();
}

} // namespace

std::string accuracyHtml(const AccuracyRun& run) {
    std::ostringstream html;
    html << "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>iblbake accuracy: "
         << escape(run.input)
         << "</title>\n<style>body{font-family:sans-serif;margin:20px;max-width:1100px}"
            "table{border-collapse:collapse;font-size:12px}td,th{border:1px solid #ccc;padding:2px 6px}"
            "tr.preset{font-weight:bold}section{margin-bottom:32px}</style></head><body>\n"
         << "<h1>What accuracy costs in time</h1>\n<p>Input <code>" << escape(run.input) << "</code>, "
         << run.sourceFaceSize << " px source faces, " << escape(run.backend) << ", " << run.hardwareThreads
         << " hardware threads, load average " << escape(run.load) << "; times are medians of " << run.repeats
         << " runs" << (run.quick ? " (quick sweep)" : "")
         << ". Orange: the Pareto front (no other setting is "
         << "both faster and more accurate); red squares: presets.</p>\n";
    for (const AccuracyStage& stage : run.stages)
        html << "<section><h2>" << escape(stage.title) << "</h2>\n<p>Reference: " << escape(stage.reference)
             << ".<br>Error: " << escape(stage.errorMetric)
             << ".<br>Max error: " << escape(stage.maxErrorMetric)
             << ".<br>Energy error: " << escape(stage.energyErrorMetric)
             << ".<br>Time: " << escape(stage.timeMeaning) << ".</p>\n"
             << plot(stage) << table(stage) << "</section>\n";
    html << "</body></html>\n";
    return html.str();
}

} // namespace ibl
