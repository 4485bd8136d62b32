#include "bench/quality_plot.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sys/wait.h>

#include "core/error.h"

namespace tyndall::bench {

std::string rowSlug(const std::string& label) {
    std::string row;
    for (unsigned char c : label)
        if (std::isalnum(c)) row += char(std::tolower(c));
        else if (!row.empty() && row.back() != '-') row += '-';
    while (!row.empty() && row.back() == '-') row.pop_back();
    return row;
}

namespace {
/// `text` with its commas made semicolons: one CSV field, no quoting needed.
std::string csvField(std::string text) {
    std::replace(text.begin(), text.end(), ',', ';');
    return text;
}
/// `text` as one shell word.
std::string shellQuoted(const std::string& text) {
    std::string q = "'";
    for (char c : text) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
}
/// `text` as a gnuplot string literal.
std::string gnuplotQuoted(const std::string& text) {
    std::string q = "\"";
    for (char c : text) q += c == '"' || c == '\\' ? std::string("\\") + c : std::string(1, c);
    return q + "\"";
}
std::string formatted(double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.9g", x);
    return buf;
}
std::ofstream openForWriting(const std::string& path) {
    std::ofstream out(path);
    if (!out) throw Error("cannot write '" + path + "'");
    return out;
}
}  // namespace

void writePlotData(const std::string& prefix, const std::vector<PlotPanel>& panels, double alpha,
                   const std::string& xLabel) {
    const std::string name = std::filesystem::path(prefix).filename().string();
    std::ofstream csv = openForWriting(prefix + ".csv");
    csv << "scene,row,x,rel_rmse\n";
    for (const auto& [scene, curves] : panels)
        for (const Curve& c : curves)
            for (auto [x, y] : c.points) csv << csvField(scene) << ',' << rowSlug(c.label) << ',' << formatted(x) << ',' << formatted(y) << '\n';
    if (!csv.flush()) throw Error("cannot write '" + prefix + ".csv'");

    const int columns = std::min<int>(3, std::max<int>(1, int(panels.size())));
    const int rows = (int(panels.size()) + columns - 1) / columns;
    std::ofstream gp = openForWriting(prefix + ".gp");
    gp << "# Relative RMSE against " << xLabel << ", log-log, one panel per scene (tyndall_quality).\n"
       << "# Run in this folder: gnuplot " << name << ".gp  ->  " << name << ".png\n"
       << "set datafile separator ','\n"
       << "set terminal pngcairo size " << 480 * columns << ',' << 360 * std::max(1, rows) << " font ',9'\n"
       << "set output " << gnuplotQuoted(name + ".png") << "\n"
       << "set multiplot layout " << std::max(1, rows) << ',' << columns << "\n"
       << "set logscale xy\nset grid\nset key top right\n"
       << "set xlabel " << gnuplotQuoted(xLabel) << "\nset ylabel 'relative RMSE'\n"
       << "data = " << gnuplotQuoted(name + ".csv") << "\n";
    const std::string slope = formatted(alpha / 2);
    for (const auto& [scene, curves] : panels) {
        gp << "set title " << gnuplotQuoted(scene) << "\nplot ";
        for (const Curve& c : curves)
            gp << "data using 3:(strcol(1) eq " << gnuplotQuoted(csvField(scene)) << " && strcol(2) eq "
               << gnuplotQuoted(rowSlug(c.label))
               << " ? $4 : NaN) with linespoints title " << gnuplotQuoted(c.label) << ", \\\n     ";
        if (!curves.empty() && !curves[0].points.empty()) {
            auto [xe, ye] = curves[0].points.back();
            gp << "(" << formatted(ye) << " * (x / " << formatted(xe) << ") ** (-" << slope
               << ")) with lines dashtype 2 lc 'grey' title 'slope -" << slope << "'\n";
        } else {
            gp << "NaN notitle\n";
        }
    }
    gp << "unset multiplot\n";
    if (!gp.flush()) throw Error("cannot write '" + prefix + ".gp'");
}

bool runGnuplot(const std::string& prefix, std::string* why) {
    std::filesystem::path p(prefix);
    const std::string dir = p.has_parent_path() ? p.parent_path().string() : ".";
    const std::string command = "cd " + shellQuoted(dir) + " && gnuplot " + shellQuoted(p.filename().string() + ".gp");
    const int status = std::system(command.c_str());
    if (status != -1 && WIFEXITED(status) && WEXITSTATUS(status) == 0) return true;
    if (status != -1 && WIFEXITED(status) && WEXITSTATUS(status) == 127)
        *why = "gnuplot not found (Debian package gnuplot-nox)";
    else
        *why = "gnuplot failed on " + prefix + ".gp";
    return false;
}

}  // namespace tyndall::bench
