// Issue 52's benchmark (not a test): can the reader of the glyph kinds (tests/render/
// GlyphReader.h, the sphere test's k-nearest-neighbour classifier on 22 features, unchanged)
// tell the kinds apart on real anatomy? ch2better + AAL, the whole brain seen from the left, at
// 1024 and 512 px, isosurface and composite, headlight and a light from the upper left; ten
// lateral left-hemisphere regions in two folds of five, each fold given the five kinds under
// several permuted assignments. A glyph patch of one fold is classified by the patches of the
// other fold only (regions distinct between training and testing, so a region's own shading is
// no cue). Truth per pixel: the AAL label at the ray's reported sample (the isosurface's hit,
// composite's 0.5 opacity point), searched 1 mm before to 3 mm beyond it. Prints per view the
// accuracy and the confusion matrix, the glyph blobs' sizes against the glyph's disc, and per
// region with >= 2,000 visible pixels how many fully visible glyphs it carries; writes the
// renders and a crop per kind to OUT.
// MVW_GLYPH_STUDY picks the anatomy (default brain, the above):
//   t1: the real T1 MPRAGE (MVW_GLYPH_T1: ../shared/data/mr-t1-t2-asl, series 5) with AAL placed
//       on it by MVW_GLYPH_T1_TRANSFORM (ch2better registered rigidly to the T1 by `mvw register`:
//       tests/bench/glyph-legibility makes it), merged into lobes per side and grown through
//       the white matter (writeLobes), seen from above on an axial cut at 60 % of its height
//       (the T1 keeps its scalp, so the brain shows on the cut face); the ten lobes with the
//       most visible pixels in each view, alternately in two folds;
//   cranium: the Cranium CT with the PET-like volume registered rigidly, seen from above on an
//       axial cut at 55 % of its height (the whole head), the functional window [1.3, 3] cut into
//       five classes of five kinds (class kinds), each permutation turning the kinds one class on;
//       a patch is classified by the other permutations' patches only, so a kind is read on
//       other classes than it was learnt on.
//   [MVW_GLYPH_RADIUS_PX=R] [MVW_GLYPH_LAYER_RADII=L] [MVW_GLYPH_ON_SURFACE=0|1]
//   [MVW_GLYPH_MODES=isosurface|composite] (one mode only, for a quicker comparison)
//   [MVW_GLYPH_ZOOM=Z] (the views' zoom: default 1, the T1 1.3; the Cranium's two hot lesions
//   of 7 and 9 mm carry a glyph or two at the whole head's scale, sample_configs/
//   cranium_glyph_kinds.json looks at them at zoom 3)
//   [MVW_GLYPH_STUDY=brain|t1|cranium] mvw_glyph_legibility_bench DATA_DIR OUT
//   [PERMUTATIONS] [SIZES...]
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include <glm/gtc/matrix_inverse.hpp>
#include <nlohmann/json.hpp>

#include "GlyphReader.h"
#include "mvw/config/StudyConfig.h"
#include "mvw/core/GlyphDefaults.h"
#include "mvw/io/LabelTable.h"
#include "mvw/io/Png.h"
#include "mvw/io/VolumeReader.h"
#include "mvw/io/VolumeWriter.h"
#include "mvw/render/GlContext.h"
#include "mvw/render/GlyphMap.h"
#include "mvw/render/VolumeRenderer.h"
#include "mvw/study/Session.h"

namespace {

namespace reader = mvw::test::reader;
using mvw::Image;

const std::vector<std::string> kKinds = {"bumps", "rings", "ridges", "cones", "crosses"};
const mvw::GlyphKind kKindValues[] = {mvw::GlyphKind::Bumps, mvw::GlyphKind::Rings,
                                      mvw::GlyphKind::Ridges, mvw::GlyphKind::Cones,
                                      mvw::GlyphKind::Crosses};
// The Cranium's class kinds: the PET-like volume's window cut into five classes.
constexpr double kClassLow = 1.3, kClassHigh = 3.0;
// Two folds of five lateral regions each, spread over the hemisphere alike (the left one;
// MVW_GLYPH_SIDE=right: the same regions of the right hemisphere, seen from the right).
std::vector<std::vector<std::string>> kFolds = {
    {"Precentral_L", "Frontal_Mid_L", "Temporal_Sup_L", "Parietal_Inf_L", "Occipital_Mid_L"},
    {"Postcentral_L", "Frontal_Inf_Tri_L", "Temporal_Mid_L", "SupraMarginal_L", "Frontal_Sup_L"}};

// The kind of region i of fold f under permutation p: every permutation a different one, the
// two folds shifted against each other.
int kindOf(int f, int i, int p) { return (i + p * (f == 0 ? 1 : 2) + f) % 5; }

struct Condition {
  int size;
  std::string mode;
  bool lit;
  std::string name() const {
    return std::to_string(size) + " px " + mode + (lit ? " lit" : " headlight");
  }
};

struct RegionCount {
  long visible = 0;
  int patches = 0, full = 0;
};

// A region whose pixels carry one kind: a label (fold 0 or 1, index in its fold), or a class
// (the Cranium: id class + 1, fold -1, its group the permutation).
struct Region {
  int id = 0, fold = -1, index = 0;
  std::string name;
};

// The T1's label map: AAL's 116 labels merged into lobes per side, and the white matter
// between them (ch2better's brain, where AAL has no label) given the nearest lobe by up to 12
// one-voxel dilations, so that a lobe on the cut face is a region a glyph fits in rather than
// a cortical ribbon. Written as OUT/lobes.nii.gz with its label table beside it.
const std::vector<std::pair<std::string, std::vector<std::string>>> kLobes = {
    {"Frontal",
     {"Frontal_", "Precentral", "Rolandic", "Supp_Motor", "Olfactory", "Rectus", "Paracentral"}},
    {"Parietal", {"Parietal_", "Postcentral", "SupraMarginal", "Angular", "Precuneus"}},
    {"Temporal", {"Temporal_", "Heschl", "Hippocampus", "ParaHippocampal", "Amygdala", "Fusiform"}},
    {"Occipital", {"Occipital_", "Calcarine", "Cuneus", "Lingual"}},
    {"Limbic", {"Insula", "Cingulum_"}},
    {"Deep", {"Caudate", "Putamen", "Pallidum", "Thalamus"}},
    {"Cerebellum", {"Cerebelum_", "Vermis"}}};

std::string lobeName(int id) {
  return kLobes[std::size_t((id - 1) / 2)].first + ((id - 1) % 2 ? "_R" : "_L");
}

std::filesystem::path writeLobes(const std::filesystem::path& data,
                                 const std::filesystem::path& out) {
  const mvw::Volume aal = mvw::io::readVolume(data / "mricron/aal.nii.gz");
  const mvw::Volume brain = mvw::io::readVolume(data / "mricron/ch2better.nii.gz");
  const glm::ivec3 n = aal.dimensions();
  // ch2better (0.5 mm) at an AAL voxel (1 mm): inside the brain where it is above 0.
  const glm::dmat4 brainFromAal = glm::inverse(brain.worldFromIndex()) * aal.worldFromIndex();
  std::vector<bool> inBrain(std::size_t(n.x) * n.y * n.z, false);
  for (int k = 0; k < n.z; ++k)
    for (int j = 0; j < n.y; ++j)
      for (int i = 0; i < n.x; ++i) {
        const glm::ivec3 b(glm::round(glm::dvec3(brainFromAal * glm::dvec4(i, j, k, 1.0))));
        if (glm::all(glm::greaterThanEqual(b, glm::ivec3(0))) &&
            glm::all(glm::lessThan(b, brain.dimensions())))
          inBrain[(std::size_t(k) * n.y + j) * n.x + i] = brain.value(b.x, b.y, b.z) > 0.0;
      }
  const auto table =
      mvw::io::readLabelTable(*mvw::io::labelTableBeside(data / "mricron/aal.nii.gz"));
  std::map<int, int> lobeOf;  // AAL label -> lobe id (1 + 2 lobe + right)
  for (const auto& [label, name] : table)
    for (std::size_t l = 0; l < kLobes.size(); ++l)
      for (const std::string& prefix : kLobes[l].second)
        if (name.rfind(prefix, 0) == 0)
          lobeOf[label] =
              1 + 2 * int(l) + (name.size() > 2 && name.substr(name.size() - 2) == "_R");
  mvw::Volume lobes(n, 1, mvw::ScalarType::Int16, aal.worldFromIndex());
  std::vector<int> id(std::size_t(n.x) * n.y * n.z, 0);
  auto at = [&](int i, int j, int k) { return (std::size_t(k) * n.y + j) * n.x + i; };
  for (int k = 0; k < n.z; ++k)
    for (int j = 0; j < n.y; ++j)
      for (int i = 0; i < n.x; ++i) {
        const auto it = lobeOf.find(int(aal.value(i, j, k)));
        id[at(i, j, k)] = it == lobeOf.end() ? 0 : it->second;
      }
  for (int pass = 0; pass < 12; ++pass) {
    std::vector<int> next = id;
    for (int k = 1; k < n.z - 1; ++k)
      for (int j = 1; j < n.y - 1; ++j)
        for (int i = 1; i < n.x - 1; ++i) {
          if (id[at(i, j, k)] || !inBrain[at(i, j, k)]) continue;
          for (const glm::ivec3 d :
               {glm::ivec3(1, 0, 0), glm::ivec3(-1, 0, 0), glm::ivec3(0, 1, 0),
                glm::ivec3(0, -1, 0), glm::ivec3(0, 0, 1), glm::ivec3(0, 0, -1)})
            if (const int v = id[at(i + d.x, j + d.y, k + d.z)]) {
              next[at(i, j, k)] = v;
              break;
            }
        }
    id = std::move(next);
  }
  for (int k = 0; k < n.z; ++k)
    for (int j = 0; j < n.y; ++j)
      for (int i = 0; i < n.x; ++i) lobes.setValue(i, j, k, 0, id[at(i, j, k)]);
  const std::filesystem::path file = out / "lobes.nii.gz";
  mvw::io::writeVolume(lobes, file);
  std::ofstream names(out / "lobes.nii.txt");
  for (int l = 1; l <= 2 * int(kLobes.size()); ++l) names << l << " " << lobeName(l) << "\n";
  return file;
}

const char* env(const char* name) {
  const char* v = std::getenv(name);
  if (!v || !*v) {
    std::fprintf(stderr, "%s must be set (see tests/bench/glyph-legibility)\n", name);
    std::exit(2);
  }
  return v;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: %s DATA_DIR OUT [PERMUTATIONS] [SIZES...]\n", argv[0]);
    return 2;
  }
  const std::filesystem::path data = argv[1], out = argv[2];
  const int perms = argc > 3 ? std::atoi(argv[3]) : 3;
  std::vector<int> sizes;
  for (int a = 4; a < argc; ++a) sizes.push_back(std::atoi(argv[a]));
  if (sizes.empty()) sizes = {1024, 512};
  std::filesystem::create_directories(out);

  const std::string scene =
      std::getenv("MVW_GLYPH_STUDY") ? std::getenv("MVW_GLYPH_STUDY") : "brain";
  if (scene != "brain" && scene != "t1" && scene != "cranium") {
    std::fprintf(stderr, "MVW_GLYPH_STUDY: '%s' is not brain, t1 or cranium\n", scene.c_str());
    return 2;
  }
  const bool classes = scene == "cranium";
  const char* sideEnv = std::getenv("MVW_GLYPH_SIDE");
  const std::string side = sideEnv ? sideEnv : "left";
  if (side != "left" && side != "right") {
    std::fprintf(stderr, "MVW_GLYPH_SIDE: '%s' is not left or right\n", side.c_str());
    return 2;
  }
  if (side == "right")
    for (auto& fold : kFolds)
      for (std::string& name : fold) name.back() = 'R';
  std::vector<Condition> conditions;
  const char* onlyMode = std::getenv("MVW_GLYPH_MODES");
  for (int size : sizes)
    for (const char* mode : {"isosurface", "composite"})
      for (bool lit : {false, true})
        if (!onlyMode || std::string(onlyMode) == mode) conditions.push_back({size, mode, lit});
  // One study, every view: plain (no glyphs) first, then each permutation's.
  nlohmann::json views = nlohmann::json::array();
  for (std::size_t c = 0; c < conditions.size(); ++c)
    for (int p = -1; p < perms; ++p) {
      const Condition& k = conditions[c];
      std::string name = "c";  // "c" + std::to_string(c) trips GCC 12's -Wrestrict
      name += std::to_string(c) + "p" + std::to_string(p + 1);
      nlohmann::json v = {{"name", name},     {"mode", k.mode},   {"view", side},
                          {"width", k.size},  {"height", k.size}, {"jitter", false},
                          {"annotate", false}};
      if (k.mode == "isosurface")
        v["iso"] = scene == "brain" ? 60 : scene == "t1" ? 250 : -300;
      else
        v["preset"] = classes ? "ct-muscle-bone" : "mr-default";
      if (scene != "brain") {
        v["view"] = "superior";
        v["crop_max"] = {1, 1, classes ? 0.55 : 0.6};
      }
      if (scene == "t1") v["zoom"] = 1.3;
      if (const char* zoom = std::getenv("MVW_GLYPH_ZOOM")) v["zoom"] = std::atof(zoom);
      if (k.lit) v["light"] = {-0.8, 0.8};
      if (classes) {
        v["functional_window"] = {kClassLow, kClassHigh};
        v["glyphs"] = {{"class_kinds", kKinds}};
      } else if (scene == "t1") {
        // Only so that the view plans with the kinds' spacing: each view's own ten lobes
        // replace them.
        nlohmann::json labels = nlohmann::json::object();
        for (int l = 0; l < 5; ++l) labels[lobeName(1 + 2 * l)] = kKinds[std::size_t(l)];
        v["glyphs"] = {{"labels", labels}};
      } else {
        // The brain's ten regions.
        nlohmann::json labels = nlohmann::json::object();
        for (int f = 0; f < 2; ++f)
          for (int i = 0; i < 5; ++i)
            labels[kFolds[std::size_t(f)][std::size_t(i)]] =
                kKinds[std::size_t(kindOf(f, i, std::max(p, 0)))];
        v["glyphs"] = {{"labels", labels}};
      }
      views.push_back(v);
    }
  nlohmann::json study = {
      {"anatomical", {{"path", (data / "mricron/ch2better.nii.gz").string()}}},
      {"functional", {{"path", (data / "mricron/aal.nii.gz").string()}, {"kind", "labels"}}},
      {"render", {{"views", views}}}};
  if (scene == "t1") {
    study["anatomical"] = {{"path", env("MVW_GLYPH_T1")}, {"series", "5"}};
    study["functional"] = {{"path", writeLobes(data, out).string()}, {"kind", "labels"}};
    study["registration"] = {{"method", "file"}, {"transform", env("MVW_GLYPH_T1_TRANSFORM")}};
  } else if (classes) {
    study["anatomical"] = {{"path", (data / "cranium/cranium.nii.gz").string()}};
    study["functional"] = {{"path", (data / "derived/pet_like.nii.gz").string()}, {"kind", "pet"}};
    study["registration"] = {{"method", "rigid"}};
  }
  std::map<int, std::string> labelNames;  // the T1's lobes
  for (int l = 1; l <= 2 * int(kLobes.size()); ++l) labelNames[l] = lobeName(l);
  const std::filesystem::path configFile = out / "glyph-legibility.json";
  std::ofstream(configFile) << study.dump(1);

  mvw::study::Session session(mvw::config::loadStudyConfig(configFile));
  auto context = mvw::render::createHeadlessContext({16, 16});
  session.load({});
  mvw::render::VolumeRenderer renderer(*context, session.anatomical());
  session.attach(renderer);
  const std::vector<mvw::study::PlannedView> planned = session.views(renderer);
  const mvw::Volume& labels = *session.functional();
  const glm::dmat4 indexFromAnatomical =
      glm::inverse(labels.worldFromIndex()) * glm::inverse(session.anatomicalFromFunctional());
  auto valueAt = [&](const glm::dvec3& world) {
    const glm::dvec3 ijk = glm::dvec3(indexFromAnatomical * glm::dvec4(world, 1.0));
    const glm::ivec3 n = labels.dimensions(), i(glm::round(ijk));
    if (glm::any(glm::lessThan(i, glm::ivec3(0))) || glm::any(glm::greaterThanEqual(i, n)))
      return 0.0;
    return labels.value(i.x, i.y, i.z);
  };
  auto labelAt = [&](const glm::dvec3& world) { return int(valueAt(world)); };

  const char* what = scene == "brain" ? (side == "right" ? "ch2better + AAL, right view"
                                                         : "ch2better + AAL, left view")
                     : scene == "t1"  ? "real T1 (series 5) + AAL placed rigidly, axial cut"
                                      : "Cranium CT + PET-like class kinds, axial cut";
  std::printf("glyph legibility (issue 52): %s, %d permutations, %s %s\n", what, perms,
              context->backend().c_str(), context->renderer().c_str());
  std::map<int, std::vector<reader::Tile>> bySize;
  std::size_t view = 0;
  for (std::size_t c = 0; c < conditions.size(); ++c) {
    const Condition& k = conditions[c];
    const mvw::render::RenderedFrame plain = [&] {
      mvw::render::RenderSettings s = planned[view++].settings;
      s.glyphs.on = false;
      return renderer.render(s);
    }();
    const int w = plain.image.width, h = plain.image.height;
    // The truth: region (label) per pixel, -1 where no ray meets the brain.
    std::vector<int> region(std::size_t(w) * h, -1);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const float t = plain.image.depth[std::size_t(y) * w + x];
        if (t < 0.0f) continue;
        const mvw::render::WorldRay ray = mvw::render::rayThrough(
            plain.camera, {(x + 0.5) / w * 2.0 - 1.0, 1.0 - (y + 0.5) / h * 2.0});
        int label = 0;
        if (classes) {
          // The class of the PET-like value just inside the surface (0: below the window).
          const double v = valueAt(ray.origin + (t + 0.5) * ray.direction);
          if (v >= kClassLow)
            label = 1 + std::min(4, int(5.0 * (v - kClassLow) / (kClassHigh - kClassLow)));
        } else {
          for (double dt = -1.0; dt <= 3.0 && label == 0; dt += 0.25)
            label = labelAt(ray.origin + (t + dt) * ray.direction);
        }
        region[std::size_t(y) * w + x] = label;
      }
    const mvw::render::WorldRay r0 = mvw::render::rayThrough(plain.camera, {0.0, 0.0});
    const mvw::render::WorldRay r1 = mvw::render::rayThrough(plain.camera, {2.0 / w, 0.0});
    const double mmPerPixel = glm::length(r1.origin - r0.origin);
    // How squarely the surface faces the viewer, |n . v| (n from the reported samples of the
    // neighbouring pixels; -1 where unknown or where the depth jumps: a fold's edge).
    std::vector<double> facing(region.size(), -1.0);
    auto hitAt = [&](int x, int y) {
      const mvw::render::WorldRay ray = mvw::render::rayThrough(
          plain.camera, {(x + 0.5) / w * 2.0 - 1.0, 1.0 - (y + 0.5) / h * 2.0});
      return ray.origin + double(plain.image.depth[std::size_t(y) * w + x]) * ray.direction;
    };
    for (int y = 1; y < h - 1; ++y)
      for (int x = 1; x < w - 1; ++x) {
        auto t = [&](int xx, int yy) { return plain.image.depth[std::size_t(yy) * w + xx]; };
        if (t(x - 1, y) < 0 || t(x + 1, y) < 0 || t(x, y - 1) < 0 || t(x, y + 1) < 0) continue;
        if (std::abs(t(x + 1, y) - t(x - 1, y)) > 8.0 * mmPerPixel ||
            std::abs(t(x, y + 1) - t(x, y - 1)) > 8.0 * mmPerPixel)
          continue;
        const glm::dvec3 n = glm::normalize(
            glm::cross(hitAt(x + 1, y) - hitAt(x - 1, y), hitAt(x, y + 1) - hitAt(x, y - 1)));
        facing[std::size_t(y) * w + x] = std::abs(glm::dot(n, r0.direction));
      }
    // The regions of this view: the brain's named ten; on the T1 the ten labels with the most
    // visible pixels, alternately in the two folds; on the Cranium the five classes.
    std::vector<Region> regions;
    if (scene == "brain") {
      for (int f = 0; f < 2; ++f)
        for (int i = 0; i < 5; ++i)
          for (const mvw::render::LabelGlyph& g : planned[view].settings.glyphLabels)
            if (g.name == kFolds[std::size_t(f)][std::size_t(i)])
              regions.push_back({g.label, f, i, g.name});
    } else if (scene == "t1") {
      std::map<int, long> area;
      for (int q : region)
        if (q > 0) ++area[q];
      std::vector<std::pair<long, int>> byArea;
      for (const auto& [label, n] : area) byArea.push_back({-n, label});
      std::sort(byArea.begin(), byArea.end());
      for (std::size_t r = 0; r < std::min<std::size_t>(10, byArea.size()); ++r) {
        const int label = byArea[r].second;
        const auto name = labelNames.find(label);
        regions.push_back({label, int(r % 2), int(r / 2),
                           name != labelNames.end() ? name->second : std::to_string(label)});
      }
    } else {
      for (int cls = 0; cls < 5; ++cls)
        regions.push_back({cls + 1, -1, cls, "class " + std::to_string(cls + 1)});
    }
    // Blobs by how the surface under them faces the viewer: [facing bin][speck, partial, whole,
    // run together]; blobs that span a fold (depth range over a glyph diameter).
    std::array<std::array<int, 4>, 3> byFacing{};
    int acrossFold = 0;
    long changed = 0, changedInBig = 0, chosenPixels = 0;
    std::vector<reader::Tile> tiles;
    std::map<int, RegionCount> counts;  // by label, summed over the permutations
    std::vector<double> areas;          // blob area / glyph disc, blobs in a chosen region
    double glyphRadiusPx = 0.0, diameterMm = 0.0;
    for (int p = 0; p < perms; ++p) {
      mvw::render::RenderSettings s = planned[view++].settings;
      // Another screen radius than the product's floor (kGlyphKindRadiusPixels), as the sphere
      // test's MVW_KIND_PX: the same blue-noise map at the spacing that gives it.
      if (const char* px = std::getenv("MVW_GLYPH_RADIUS_PX")) {
        const double spacing = std::atof(px) * mmPerPixel / (0.5 * mvw::kBlueNoiseDiameterFraction);
        s.glyphMap = mvw::render::blueNoiseGlyphMap(
            spacing, mvw::kBlueNoiseDiameterFraction * spacing, s.glyphMap.seed);
        s.glyphDiameterMm = mvw::kBlueNoiseDiameterFraction * spacing;
      }
      // Composite's one glyph layer (RenderSettings::glyphLayerMm, issue 52's prototype), in
      // glyph radii so that one value suits every size.
      if (const char* layer = std::getenv("MVW_GLYPH_LAYER_RADII"))
        s.glyphLayerMm = std::atof(layer) * 0.5 * s.glyphDiameterMm;
      // Glyphs on the visible surface (RenderSettings::glyphs.onSurface, "on_surface") or not,
      // whatever the view says.
      if (const char* on = std::getenv("MVW_GLYPH_ON_SURFACE")) s.glyphs.onSurface = *on == '1';
      glyphRadiusPx = 0.5 * s.glyphDiameterMm / mmPerPixel;
      diameterMm = s.glyphDiameterMm;
      // Each region's kind and group under permutation p; the settings say the same.
      std::map<int, int> kindOfLabel, foldOfLabel;
      for (const Region& r : regions) {
        kindOfLabel[r.id] = r.fold < 0 ? (r.index + p) % 5 : kindOf(r.fold, r.index, p);
        foldOfLabel[r.id] = r.fold < 0 ? p : r.fold;
      }
      if (scene == "t1") {
        s.glyphLabels.clear();
        for (const Region& r : regions)
          s.glyphLabels.push_back({r.id, kKindValues[kindOfLabel[r.id]], r.name});
        std::sort(s.glyphLabels.begin(), s.glyphLabels.end(),
                  [](const auto& a, const auto& b) { return a.label < b.label; });
      } else if (classes) {
        s.glyphs.classKinds.clear();
        for (const Region& r : regions)
          s.glyphs.classKinds.push_back(kKindValues[kindOfLabel[r.id]]);
      }
      for (int q : region) chosenPixels += q > 0 && kindOfLabel.count(q);
      const mvw::render::RenderedFrame glyphs = renderer.render(s);
      const std::string stem =
          std::to_string(k.size) + "-" + k.mode + (k.lit ? "-lit" : "") + "-p" + std::to_string(p);
      mvw::io::writePng(glyphs.image, out / (stem + ".png"));
      if (p == 0) mvw::io::writePng(plain.image, out / (stem + "-plain.png"));
      for (std::size_t i = 0; i < region.size(); ++i)
        if (kindOfLabel.count(region[i])) ++counts[region[i]].visible;
      const std::vector<double> d = reader::glyphChange(glyphs.image, plain.image);
      if (p == 0) {
        // What the reader sees: white where the glyphs changed a pixel by kChanged, grey for the
        // chosen regions.
        Image change(w, h);
        for (std::size_t i = 0; i < region.size(); ++i) {
          const std::uint8_t v = std::abs(d[i]) >= reader::kChanged ? 255
                                 : kindOfLabel.count(region[i])     ? 70
                                                                    : 0;
          std::fill_n(change.rgba.begin() + long(4 * i), 3, v);
          change.rgba[4 * i + 3] = 255;
        }
        mvw::io::writePng(change, out / (stem + "-change.png"));
      }
      for (const reader::Blob& blob : reader::changedBlobs(d, w, h)) {
        const int label = region[std::size_t(blob.middle)];
        if (!kindOfLabel.count(label) || blob.edge) continue;
        int inside = 0;
        for (int q : blob.pixels) inside += region[std::size_t(q)] == label;
        const double area = double(blob.pixels.size()) / (M_PI * glyphRadiusPx * glyphRadiusPx);
        areas.push_back(area);
        double f = 0.0, fn = 0.0, tMin = 1e30, tMax = -1e30;
        for (int q : blob.pixels) {
          if (facing[std::size_t(q)] >= 0.0) f += facing[std::size_t(q)], fn += 1.0;
          const double tq = plain.image.depth[std::size_t(q)];
          if (tq >= 0.0) tMin = std::min(tMin, tq), tMax = std::max(tMax, tq);
        }
        f = fn > 0.0 ? f / fn : 0.0;
        acrossFold += tMax - tMin > diameterMm;
        ++byFacing[f >= 0.7   ? 0
                   : f >= 0.4 ? 1
                              : 2][area < 0.25   ? 0
                                   : area < 0.7  ? 1
                                   : area <= 1.6 ? 2
                                                 : 3];
        for (int q : blob.pixels)
          if (std::abs(d[std::size_t(q)]) >= reader::kChanged) {
            ++changed;
            if (area > 1.6) ++changedInBig;
          }
        // Inside its region (a patch across two regions has no one kind to be read).
        if (inside < 0.9 * double(blob.pixels.size())) continue;
        if (area >= 0.7 && area <= 1.6) ++counts[label].full;
        if (!reader::isGlyphPatch(blob, glyphRadiusPx)) continue;
        ++counts[label].patches;
        tiles.push_back({kindOfLabel[label], foldOfLabel[label],
                         reader::describe(d, w, blob.pixels, glyphRadiusPx)});
      }
      // A crop per kind (the first permutation at the largest size): the region's middle, 160 px
      // enlarged three times.
      if (p == 0 && k.size == sizes.front())
        for (const auto& [label, kind] : kindOfLabel) {
          double cx = 0.0, cy = 0.0, n = 0.0;
          for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x)
              if (region[std::size_t(y) * w + x] == label) cx += x, cy += y, n += 1.0;
          if (n < 1.0) continue;
          const int x0 = std::clamp(int(cx / n) - 80, 0, w - 160);
          const int y0 = std::clamp(int(cy / n) - 80, 0, h - 160);
          Image crop(480, 480);
          for (int y = 0; y < 480; ++y)
            for (int x = 0; x < 480; ++x)
              std::copy_n(glyphs.image.pixel(x0 + x / 3, y0 + y / 3), 4, crop.pixel(x, y));
          mvw::io::writePng(crop, out / (stem + "-" + kKinds[std::size_t(kind)] + "-" +
                                         std::to_string(label) + ".png"));
        }
    }
    std::printf("\n== %s: glyph diameter %.2f mm, radius %.1f px (%.3f mm per px)\n",
                k.name().c_str(), diameterMm, glyphRadiusPx, mmPerPixel);
    std::sort(areas.begin(), areas.end());
    auto share = [&](double lo, double hi) {
      return 100.0 *
             double(std::count_if(areas.begin(), areas.end(),
                                  [&](double a) { return a >= lo && a < hi; })) /
             double(std::max<std::size_t>(areas.size(), 1));
    };
    std::printf(
        "blobs in the chosen regions: %zu; area / glyph disc: median %.2f; < 0.25 (specks) %.0f "
        "%%, 0.25-0.7 (partial) %.0f %%, 0.7-1.6 (whole) %.0f %%, > 1.6 (run together) %.0f %%\n",
        areas.size(), areas.empty() ? 0.0 : areas[areas.size() / 2], share(0.0, 0.25),
        share(0.25, 0.7), share(0.7, 1.6), share(1.6, 1e9));
    std::printf("blobs spanning a fold (depth range over a glyph diameter): %.0f %%\n",
                100.0 * acrossFold / double(std::max<std::size_t>(areas.size(), 1)));
    const char* bins[] = {"faces the viewer (|n.v| >= 0.7)", "oblique (0.4-0.7)",
                          "grazing (< 0.4)"};
    for (int b = 0; b < 3; ++b) {
      const auto& row = byFacing[std::size_t(b)];
      const int n = row[0] + row[1] + row[2] + row[3];
      std::printf(
          "  %-32s %4d blobs: specks %3.0f %%, partial %3.0f %%, whole %3.0f %%, "
          "run together %3.0f %%\n",
          bins[b], n, 100.0 * row[0] / std::max(n, 1), 100.0 * row[1] / std::max(n, 1),
          100.0 * row[2] / std::max(n, 1), 100.0 * row[3] / std::max(n, 1));
    }
    std::printf(
        "changed pixels: %.1f %% of the chosen regions' pixels, %.0f %% of them in blobs "
        "over 1.6 glyph discs\n",
        100.0 * double(changed) / double(std::max(chosenPixels, 1L)),
        100.0 * double(changedInBig) / double(std::max(changed, 1L)));
    std::printf("%-18s %8s %8s %8s   (per permutation)\n", "region", "visible", "patches", "whole");
    int big = 0, bigCarrying = 0;
    for (const Region& r : regions) {
      const RegionCount& rc = counts[r.id];
      const bool isBig = rc.visible / perms >= 2000, carries = rc.full >= 3 * perms;
      big += isBig, bigCarrying += isBig && carries;
      std::printf("%-18s %8ld %8.1f %8.1f%s\n", r.name.c_str(), rc.visible / perms,
                  double(rc.patches) / perms, double(rc.full) / perms,
                  isBig && !carries ? "  < 3 whole glyphs" : "");
    }
    std::printf("regions with >= 2,000 visible pixels carrying >= 3 whole glyphs: %d of %d\n",
                bigCarrying, big);
    reader::print(reader::classify(tiles, 5), kKinds, k.name().c_str());
    std::fflush(stdout);
    // Pooled per size, the group still the fold: a patch is judged by the other fold's regions
    // in every view.
    bySize[k.size].insert(bySize[k.size].end(), tiles.begin(), tiles.end());
  }
  for (const auto& [size, tiles] : bySize) {
    const std::string title = std::to_string(size) + " px, the four views pooled";
    reader::print(reader::classify(tiles, 5), kKinds, title.c_str());
  }
  return 0;
}
