#pragma once
// A study's render views turned into renderer settings, validated before any volume is read
// or GL context exists; shared by `mvw render` and `mvw bench features`.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "mvw/config/StudyConfig.h"
#include "mvw/core/Volume.h"
#include "mvw/core/WindowLevel.h"
#include "mvw/render/VolumeRenderer.h"
#include "mvw/study/ModalityDefaults.h"

namespace mvw::study {

// Command-line values that replace each view's own.
struct ViewOverrides {
  std::optional<std::string> mode, view, preset, sampling;
  // colormap: views that take one (mip, minip, average, mpr); overlay colormap: every view.
  std::optional<std::string> colormap, overlayColormap, orbitMode;
  std::optional<int> orbit;
  std::optional<int> size;
  std::optional<double> azimuth, elevation, roll, zoom, window, level, iso;
  std::optional<double> cueBrightness, cueAmount, cueContrast;
  bool noAnnotate = false;
  bool perspective = false;
};

struct PlannedView {
  config::ViewConfig config;
  render::RenderSettings settings;
  std::string presetName;  // empty until the anatomy is known: see applyDefaultPreset
};

// The config's view names and the renderer's standard views (axial, coronal and sagittal are
// inferior, anterior and left; the way back gives the six standard names).
render::StandardView standardView(config::ViewName view);
config::ViewName viewName(render::StandardView view);

// Throws InputError naming the study file for any view the renderer cannot honour.
std::vector<PlannedView> planViews(const config::StudyConfig& study,
                                   const ViewOverrides& overrides = {});

// A colour map as 256 entries: hot metal from the renderer's preset, the others from io (the
// DICOM standard palettes through vtk-dicom, the grey ramps).
ColorTable colorTable(ColorMap map);
// The renderer's settings for the view's colour maps: none for grey and for the overlay's hot
// metal (the renderer's defaults), a table otherwise.
void applyColorMaps(render::RenderSettings& settings, ColorMap image, ColorMap overlay);

// Views without a preset get the one that suits the anatomy's modality.
void applyDefaultPreset(PlannedView& view, const Volume& anatomy);

// Refuses (InputError naming `file`, the study config) what a view asks of this anatomy that
// would render nothing, before anything is rendered: a sample step too fine for a ray to carry
// (below 1/100 of the smallest voxel spacing: the steps would overflow the ray's count and its
// float distance), a crop box in mm that misses the volume, an MPR plane offset beyond it.
void checkViewsAgainstAnatomy(const std::vector<PlannedView>& views, const Volume& anatomy,
                              const std::filesystem::path& file);

// Glyph views without an attribute window (functional_window) or label classes get the one
// that suits the functional volume (defaultAttributeWindow); range: its value range.
void applyAttributeDefaults(PlannedView& view, config::FunctionalKind kind,
                            const Volume& functional, std::pair<double, double> range);

// Cropped composite and isosurface views that show the anatomy on their cut face
// (RenderSettings::cutFace) and name no window get `mpr`: the study's MPR window (its first MPR
// view's, else the modality's, ModalityDefaults::mpr), so the face shows what an MPR on that
// plane shows, in `mvw render` as in the viewer.
void applyCutFaceWindow(PlannedView& view, const WindowLevel& mpr);

// An emission image read alone (ModalityDefaults of a PET or SPECT anatomy; nothing for other
// modalities): the view the study gets where its config names none (config::ViewConfig::implied)
// becomes its MIP in the modality's colour map (grey-inverted), and every MIP or MPR view that
// names no window gets the modality's (0-5 or 0-10 SUV; without SUV 0 to the 99.5th
// percentile). `mvw render` and the viewer (study::prepareViews) share it.
void applyModalityView(PlannedView& view, const Volume& anatomy, const ModalityDefaults& defaults);

// Glyph views whose config leaves the blue-noise spacing open get it from the functional
// volume's voxel and the rendered scale (defaultGlyphSpacingMm), the diameter following.
void applyGlyphScale(PlannedView& view, const Volume& anatomy, const Volume& functional);

// Issue 15's default glyph spacing (mm): one glyph per functional voxel (the attribute's own
// resolution), but no finer than makes the weakest bump (minSize glyph radii) kGlyphMinBumpPixels
// in radius at mmPerPixel, and no coarser than kGlyphSpacingMm unless the scale demands it,
// so that a 10 mm region above the window carries at least three bumps where the image can
// show them.
// With glyph kinds (kinds), no finer than makes a full-size glyph kGlyphKindRadiusPixels in
// radius: a shape must be read.
double defaultGlyphSpacingMm(double functionalVoxelMm, double mmPerPixel, double minSize,
                             bool kinds = false);

// The inverse of planViews for one view: the config that plans back to `settings` (the
// viewer saves its panes this way). preset: its name, "" for the modality's default.
config::ViewConfig describeView(const render::RenderSettings& settings, const std::string& name,
                                const std::string& preset);

}  // namespace mvw::study
