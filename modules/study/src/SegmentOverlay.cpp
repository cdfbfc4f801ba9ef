#include "mvw/study/SegmentOverlay.h"

#include <cmath>
#include <filesystem>
#include <map>
#include <vector>

#include "mvw/core/Error.h"
#include "mvw/core/Format.h"
#include "mvw/core/Frame.h"
#include "mvw/io/DicomSeg.h"
#include "mvw/study/StudyLoader.h"

namespace mvw::study {

namespace {

// Distinct, readable on grey and on hot colour maps (Slicer's first label colours).
const glm::vec3 kPalette[] = {{0.50f, 0.68f, 0.50f}, {0.95f, 0.84f, 0.57f}, {0.69f, 0.48f, 0.39f},
                              {0.44f, 0.72f, 0.82f}, {0.85f, 0.40f, 0.33f}, {0.87f, 0.51f, 0.89f},
                              {0.56f, 0.93f, 0.56f}, {0.30f, 0.45f, 0.95f}};

}  // namespace

static SegmentOverlay readLocalSegmentOverlay(const config::VolumeSource& source,
                                              const io::ReadOptions& options);

SegmentOverlay readSegmentOverlay(const config::VolumeSource& source, const io::ReadOptions& given,
                                  const pacs::Options& pacs) {
  io::ReadOptions options = given;
  options.series = source.series;
  config::VolumeSource local = source;
  if (!source.pacs.empty()) {
    // A PACS series from its verified cache folder: a SEG is its one file; "series" chose it.
    return readLocal(source, pacs, [&](const std::filesystem::path& folder) {
      local.path = folder;
      local.series.clear();
      options.series.clear();
      std::vector<std::filesystem::path> files;
      for (const auto& e : std::filesystem::directory_iterator(local.path))
        if (e.path().extension() == ".dcm") files.push_back(e.path());
      if (files.size() == 1 && io::isDicomSegmentation(files.front())) local.path = files.front();
      return readLocalSegmentOverlay(local, options);
    });
  }
  return readLocalSegmentOverlay(local, options);
}

static SegmentOverlay readLocalSegmentOverlay(const config::VolumeSource& source,
                                              const io::ReadOptions& options) {
  SegmentOverlay out;
  if (io::isDicomSegmentation(source.path)) {
    // A SEG file is one segmentation, its frames its segments' slices: neither key applies.
    if (!source.series.empty())
      throw InputError(source.path,
                       "'segmentation.series' does not apply: a DICOM SEG file is one "
                       "segmentation");
    if (source.frame)
      throw InputError(source.path,
                       "'segmentation.frame' does not apply: a DICOM SEG's frames are its "
                       "segments' slices");
    io::Segmentation seg = io::readDicomSegmentation(source.path, options);
    for (std::size_t s = 0; s < seg.segments.size(); ++s) {
      const auto& segment = seg.segments[s];
      out.numbers.push_back(segment.number);
      out.names.push_back(segment.label.empty() ? "segment " + std::to_string(segment.number)
                                                : segment.label);
      out.colours.push_back(
          segment.rgb ? glm::vec3((*segment.rgb)[0], (*segment.rgb)[1], (*segment.rgb)[2]) / 255.0f
                      : kPalette[s % std::size(kPalette)]);
    }
    out.masks = std::move(seg.masks);
    return out;
  }
  Volume labels = io::readVolume(source.path, options);
  if (source.frame) {
    if (source.frame->mean)
      throw InputError(source.path,
                       "'segmentation.frame' cannot be \"mean\": label numbers are not averaged");
    try {
      labels = selectFrame(labels, *source.frame);
    } catch (const InputError& e) {
      throw InputError(e.file(), e.problem() + " (the study config's \"segmentation.frame\")");
    }
  }
  std::map<long long, int> component;
  const glm::ivec3 d = labels.dimensions();
  for (int k = 0; k < d.z; ++k)
    for (int j = 0; j < d.y; ++j)
      for (int i = 0; i < d.x; ++i) {
        const double v = labels.value(i, j, k);
        if (std::isnan(v) || v == 0.0) continue;
        if (v != std::floor(v))
          throw InputError(source.path,
                           "a segmentation must be a DICOM SEG or a label volume; "
                           "this one holds the non-integer value " +
                               shortNumber(v));
        if (component.emplace(static_cast<long long>(v), 0).second && component.size() > 16)
          throw InputError(source.path, "more than 16 labels: outlines take at most 16 segments");
      }
  int c = 0;
  for (auto& [label, index] : component) {
    index = c;
    out.numbers.push_back(static_cast<int>(label));
    out.names.push_back("label " + std::to_string(label));
    out.colours.push_back(kPalette[static_cast<std::size_t>(c) % std::size(kPalette)]);
    ++c;
  }
  out.masks = Volume(d, std::max(1, c), ScalarType::UInt8, labels.worldFromIndex());
  out.masks.metadata() = labels.metadata();
  for (int k = 0; k < d.z; ++k)
    for (int j = 0; j < d.y; ++j)
      for (int i = 0; i < d.x; ++i) {
        const double v = labels.value(i, j, k);
        if (std::isnan(v) || v == 0.0) continue;
        out.masks.setValue(i, j, k, component[static_cast<long long>(v)], 1.0);
      }
  return out;
}

glm::dmat4 anatomicalFromSegmentation(const SegmentOverlay& overlay, const Volume* functional,
                                      const glm::dmat4& anatomicalFromFunctional) {
  const std::string& mine = overlay.masks.metadata().frameOfReferenceUid;
  if (functional && !mine.empty() && mine == functional->metadata().frameOfReferenceUid)
    return anatomicalFromFunctional;
  return glm::dmat4(1.0);
}

}  // namespace mvw::study
