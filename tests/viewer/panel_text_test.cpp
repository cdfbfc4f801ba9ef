// The words of the viewer's panel and panes (mvw/viewer/PanelText.h), without ImGui: a text
// width of one unit a character stands in for the font.
#include "mvw/viewer/PanelText.h"

#include <string>

#include <gtest/gtest.h>

namespace mvw::viewer {
namespace {

float chars(const std::string& text) { return static_cast<float>(text.size()); }

TEST(PanelText, PaneMessagesWrapAtTheWidthAndAfterEachClause) {
  EXPECT_EQ(wrapPaneMessage("no functional volume", 100, chars), "no functional volume");
  EXPECT_EQ(wrapPaneMessage("one two three four", 9, chars), "one two\nthree\nfour");
  EXPECT_EQ(wrapPaneMessage("outside the window; scroll back", 100, chars),
            "outside the window;\nscroll back");
  // A parenthesis stays on one line, however narrow the pane.
  EXPECT_EQ(wrapPaneMessage("values (0 .. 10 SUV) here", 8, chars), "values\n(0 .. 10 SUV)\nhere");
  EXPECT_EQ(wrapPaneMessage("", 10, chars), "");
}

TEST(PanelText, RoiStatistics) {
  study::RoiStats s;
  s.voxels = 0;
  s.volumeMl = 0.0;
  EXPECT_EQ(roiStatsLines("CT", s), std::vector<std::string>{"  CT: 0 voxels, 0 ml"});
  s.voxels = 1234;
  s.volumeMl = 12.3456;
  s.max = 9.87654;
  s.mean = 3.14159;
  s.sd = 0.5;
  s.unit = "SUV";
  EXPECT_EQ(roiStatsLines("PT SUV", s),
            (std::vector<std::string>{"  PT SUV: 1234 voxels, 12.3 ml",
                                      "    max 9.877  mean 3.142  SD 0.5 SUV"}));
  s.peak = 7.25;
  s.unit.clear();
  EXPECT_EQ(roiStatsLines("MR", s).back(), "    SUVpeak 7.25 (1 cm3)");
  EXPECT_EQ(roiStatsLines("MR", s)[1], "    max 9.877  mean 3.142  SD 0.5");
}

TEST(PanelText, Labels) {
  EXPECT_EQ(sphereLabel(1, true, 7.5), "ROI 2  r 7.5 mm");
  EXPECT_EQ(sphereLabel(3, false, 10.0), "r 10.0 mm");
  render::GlyphLegendEntry e;
  e.label = "2.5 SUV";
  e.size = 0.6;
  e.kind = GlyphKind::Bumps;
  EXPECT_EQ(glyphLegendLine(e), std::string("2.5 SUV  60 % ") + glyphKindName(GlyphKind::Bumps));
  e.size = 0.0;
  EXPECT_EQ(glyphLegendLine(e), "2.5 SUV  no glyph");
}

TEST(PanelText, GlyphPickerListsNamedLabelsOrNumbers) {
  const auto named = glyphPickerLabels({{0, "background"}, {2, "liver"}, {5, "spleen"}}, 9.0);
  ASSERT_EQ(named.size(), 2u);
  EXPECT_EQ(named[0], (std::pair<int, std::string>{2, "liver"}));
  EXPECT_EQ(named[1], (std::pair<int, std::string>{5, "spleen"}));
  const auto numbered = glyphPickerLabels({}, 3.7);
  ASSERT_EQ(numbered.size(), 3u);
  EXPECT_EQ(numbered[2], (std::pair<int, std::string>{3, ""}));
  EXPECT_EQ(glyphPickerLabels({}, 1000.0).size(), 255u);
  EXPECT_TRUE(glyphPickerLabels({}, -5.0).empty());
  EXPECT_EQ(glyphPickerHeader(0), "glyph labels (all above the window)###glyph-labels");
  EXPECT_EQ(glyphPickerHeader(2), "glyph labels (2 chosen)###glyph-labels");
}

TEST(PanelText, MeasurementsRegistrationAndTitle) {
  EXPECT_EQ(sphereHeader(0, {{1.0, -2.25, 3.04}, 5.0}), "ROI 1: r 5.0 mm at 1.0, -2.2, 3.0");
  EXPECT_EQ(rulerLine(2, 12.345), "ruler 3: 12.3 mm");
  EXPECT_EQ(registrationLine("none"), "registration: none (world coordinates)");
  EXPECT_EQ(registrationLine("rigid MI, 12 iterations"), "registration: rigid MI, 12 iterations");
  EXPECT_EQ(rerunRegistrationLabel("affine"), "re-run registration (affine MI)");
  EXPECT_EQ(viewerTitle(""), "mvw view");
  EXPECT_EQ(viewerTitle("PET/CT"), "mvw view: PET/CT");
}

TEST(PanelText, PacsWindow) {
  EXPECT_EQ(serverNote({"clinic", "dicom://PACS@host:104", "MVW"}),
            "dicom://PACS@host:104  (calling AE MVW)");
  EXPECT_EQ(serverNote({"web", "https://host/dicom-web", "MVW"}), "https://host/dicom-web");
  const std::string help = noServersHelp("/home/u/.config/mvw/servers.json");
  EXPECT_EQ(help.rfind("No server: list them in /home/u/.config/mvw/servers.json as {", 0), 0u);
  EXPECT_NE(help.find("(or mvw view --servers FILE)."), std::string::npos);
}

}  // namespace
}  // namespace mvw::viewer
