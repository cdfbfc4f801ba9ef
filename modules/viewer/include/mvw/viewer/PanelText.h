#pragma once
// The words the viewer's panel and panes show (app/view draws them with Dear ImGui): wrapped
// pane messages, ROI statistics, measurement and legend labels, the glyph label picker's list,
// the PACS window's notes.
#include <cstddef>
#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "mvw/config/ServerList.h"
#include "mvw/config/StudyConfig.h"
#include "mvw/render/Annotations.h"
#include "mvw/study/RoiStatistics.h"

namespace mvw::viewer {

// A pane's "why it shows nothing" message, word-wrapped to `width` as `textWidth` measures a
// line, with a new line after each clause ending in ';'; a parenthesis (a value range) stays on
// one line.
std::string wrapPaneMessage(const std::string& message, float width,
                            const std::function<float(const std::string&)>& textWidth);

// One volume's statistics of a sphere ROI with data: its size line, then the values' lines
// (none for an ROI without voxels).
std::vector<std::string> roiStatsLines(const std::string& volume, const study::RoiStats& s);

// The label by a sphere on an MPR pane: "ROI 2  r 7.5 mm" (a pending sphere, not yet saved:
// "r 7.5 mm"); `index` counts from 0.
std::string sphereLabel(std::size_t index, bool saved, double radiusMm);

// A glyph legend's line in the panel: "2.5 SUV  60 % bumps", or "... no glyph".
std::string glyphLegendLine(const render::GlyphLegendEntry& e);

// The labels the glyph label picker lists: a label map's named labels above 0, or without names
// 1 to the functional range's top (at most 255).
std::vector<std::pair<int, std::string>> glyphPickerLabels(const std::map<int, std::string>& names,
                                                           double functionalTop);

// The picker's header: how many labels are chosen ("all above the window" for none).
std::string glyphPickerHeader(std::size_t chosen);

// The panel's lines of a sphere ROI ("ROI 1: r 5.0 mm at 1.0, 2.0, 3.0") and a ruler ("ruler
// 1: 12.3 mm"); `index` counts from 0.
std::string sphereHeader(std::size_t index, const config::SphereMeasurement& s);
std::string rulerLine(std::size_t index, double lengthMm);

// How the functional volume is placed ("registration: none (world coordinates)"), and the
// re-run button's label for the study's method ("re-run registration (affine MI)").
std::string registrationLine(const std::string& description);
std::string rerunRegistrationLabel(const std::string& method);

// The window's title: the study's name, where it has one.
std::string viewerTitle(const std::string& studyName);

// The PACS window's words: a server's address beside its name (a DIMSE server with mvw's
// calling AE title), and what to do without a server.
std::string serverNote(const config::SavedServer& server);
std::string noServersHelp(const std::filesystem::path& serversFile);

}  // namespace mvw::viewer
