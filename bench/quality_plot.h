#pragma once
// The quality study's plot as data and a script for a real plotting tool: PREFIX.csv holds every
// curve's points (scene, row as rowSlug, x, relative RMSE; no field holds a comma), PREFIX.gp is a gnuplot script that draws them
// log-log, one panel per scene, with the N^(-alpha/2) slope of a fixed schedule's noise dashed
// through the last point of each panel's first curve, into PREFIX.png.
#include <string>
#include <utility>
#include <vector>

namespace tyndall::bench {

struct Curve {
    std::string label;                              ///< the row, e.g. "LEGACY"
    std::vector<std::pair<double, double>> points;  ///< (passes or CPU seconds, relative RMSE)
};
/// A row label as a file-name and CSV part: "AUTO, PLANNED" -> "auto-planned".
std::string rowSlug(const std::string& label);

/// One panel: a scene's name and its curves.
using PlotPanel = std::pair<std::string, std::vector<Curve>>;

/// Writes PREFIX.csv and PREFIX.gp (`xLabel` names the x axis); throws Error naming a file that
/// cannot be written.
void writePlotData(const std::string& prefix, const std::vector<PlotPanel>& panels, double alpha,
                   const std::string& xLabel);

/// Runs `gnuplot PREFIX.gp` in PREFIX's folder (the script names its files without a folder).
/// False, with the reason in `why`, when gnuplot is missing (Debian package gnuplot-nox) or fails.
bool runGnuplot(const std::string& prefix, std::string* why);

}  // namespace tyndall::bench
