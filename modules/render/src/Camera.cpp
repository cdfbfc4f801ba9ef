#include "mvw/render/Camera.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace mvw::render {

namespace {

struct Basis {
  glm::dvec3 forward, up;
};

Basis standardBasis(StandardView view) {
  // LPS: +x patient left, +y posterior, +z superior.
  switch (view) {
    case StandardView::Anterior:
      return {{0, 1, 0}, {0, 0, 1}};
    case StandardView::Posterior:
      return {{0, -1, 0}, {0, 0, 1}};
    case StandardView::Left:
      return {{-1, 0, 0}, {0, 0, 1}};
    case StandardView::Right:
      return {{1, 0, 0}, {0, 0, 1}};
    case StandardView::Superior:
      return {{0, 0, -1}, {0, -1, 0}};
    case StandardView::Inferior:
      return {{0, 0, 1}, {0, -1, 0}};
  }
  return {{0, 1, 0}, {0, 0, 1}};
}

const char* kNames[] = {"anterior", "posterior", "left", "right", "superior", "inferior"};

}  // namespace

std::optional<StandardView> parseStandardView(const std::string& name) {
  for (int i = 0; i < 6; ++i)
    if (name == kNames[i]) return static_cast<StandardView>(i);
  // The MPR planes as radiology displays them: axial seen from the feet, coronal from the
  // front, sagittal from the patient's left.
  if (name == "axial") return StandardView::Inferior;
  if (name == "coronal") return StandardView::Anterior;
  if (name == "sagittal") return StandardView::Left;
  return std::nullopt;
}

std::string toString(StandardView view) { return kNames[static_cast<int>(view)]; }

WorldRay rayThrough(const Camera& camera, const glm::dvec2& ndc) {
  const glm::dvec4 nearPoint = camera.worldFromClip * glm::dvec4(ndc, -1.0, 1.0);
  const glm::dvec4 farPoint = camera.worldFromClip * glm::dvec4(ndc, 1.0, 1.0);
  WorldRay ray;
  ray.origin = glm::dvec3(nearPoint) / nearPoint.w;
  ray.direction = glm::normalize(glm::dvec3(farPoint) / farPoint.w - ray.origin);
  return ray;
}

namespace {

// Half the view's height at zoom 1 in framing radii, in an image of `aspect`: the framing
// sphere fits the shorter side; with a fitAspect of another shape, the field that shape shows
// fits whole (its height, or its width at this aspect, whichever needs more).
double fieldHalfHeight(const CameraSettings& s, double aspect) {
  if (!(s.fitAspect > 0.0) || s.fitAspect == aspect) return 1.0 / std::min(1.0, aspect);
  const double half = 1.0 / std::min(1.0, s.fitAspect);
  return std::max(half, half * s.fitAspect / aspect);
}

}  // namespace

double fittedZoom(const CameraSettings& s, glm::ivec2 imageSize) {
  const double aspect = static_cast<double>(imageSize.x) / std::max(imageSize.y, 1);
  const double zoom = s.zoom > 0 ? s.zoom : 1.0;
  if (!(s.fitAspect > 0.0) || s.fitAspect == aspect) return zoom;  // exactly: saved states
  return zoom / std::min(1.0, aspect) / fieldHalfHeight(s, aspect);
}

Camera makeCamera(const CameraSettings& s, const glm::dvec3& centre, double radius,
                  glm::ivec2 imageSize) {
  Basis b = standardBasis(s.view);
  glm::dvec3 right = glm::cross(b.forward, b.up);
  auto rotate = [](const glm::dvec3& v, const glm::dvec3& axis, double deg) {
    return glm::dvec3(glm::rotate(glm::dmat4(1.0), glm::radians(deg), axis) * glm::dvec4(v, 0.0));
  };
  // Azimuth: the camera orbits about the up axis (positive: toward the camera's right).
  b.forward = rotate(b.forward, b.up, -s.azimuthDeg);
  right = rotate(right, b.up, -s.azimuthDeg);
  // Elevation: the camera rises (positive) about its right axis.
  b.forward = rotate(b.forward, right, -s.elevationDeg);
  b.up = rotate(b.up, right, -s.elevationDeg);
  // Roll: the image turns clockwise for positive roll.
  b.up = rotate(b.up, b.forward, s.rollDeg);
  right = rotate(right, b.forward, s.rollDeg);

  Camera c;
  c.forward = glm::normalize(b.forward);
  c.up = glm::normalize(b.up);
  c.right = glm::normalize(right);
  c.perspective = s.perspective;
  c.aspect = static_cast<double>(imageSize.x) / imageSize.y;
  const double zoom = s.zoom > 0 ? s.zoom : 1.0;
  const glm::dvec3 target = centre - c.right * s.panMm.x - c.up * s.panMm.y;
  // Fit the bounding sphere in the shorter image side (of the image the zoom was set for).
  const double fitHalf = radius * fieldHalfHeight(s, c.aspect) / zoom;
  double nearPlane = 0.0, farPlane = 0.0;
  if (s.perspective) {
    c.tanHalfFov = std::tan(glm::radians(s.fovDeg) / 2.0);
    const double distance = fitHalf / c.tanHalfFov + radius;
    c.eye = target - c.forward * distance;
    nearPlane = std::max(distance - radius * 1.01, 1e-3 * distance);
    farPlane = distance + radius * 1.01;
  } else {
    c.halfHeightMm = fitHalf;
    c.eye = target - c.forward * (radius * 2.0);
    nearPlane = radius * 0.99;
    farPlane = radius * 3.01;
  }
  const glm::dmat4 viewFromWorld = glm::lookAt(c.eye, c.eye + c.forward, c.up);
  const glm::dmat4 clipFromView =
      s.perspective ? glm::perspective(2.0 * std::atan(c.tanHalfFov), c.aspect, nearPlane, farPlane)
                    : glm::ortho(-c.halfHeightMm * c.aspect, c.halfHeightMm * c.aspect,
                                 -c.halfHeightMm, c.halfHeightMm, nearPlane, farPlane);
  c.clipFromWorld = clipFromView * viewFromWorld;
  c.worldFromClip = glm::inverse(c.clipFromWorld);
  return c;
}

}  // namespace mvw::render
