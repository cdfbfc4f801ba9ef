#pragma once
// The camera in LPS world millimetres. The six standard views are named as radiologists
// name them: "anterior" looks at the patient's face (the patient's left is on the screen's
// right), "left" looks at the patient's left side, "superior" looks down from the vertex
// (anterior up), "inferior" up from the feet (anterior up, patient's right on screen left).
// The MPR names are aliases: axial = inferior, coronal = anterior, sagittal = left.
// Azimuth turns about the view's up axis, elevation about its right axis, roll about the
// line of sight; zoom > 1 magnifies; pan moves the view in screen-plane millimetres.
#include <optional>
#include <string>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace mvw::render {

enum class StandardView { Anterior, Posterior, Left, Right, Superior, Inferior };

std::optional<StandardView> parseStandardView(const std::string& name);
std::string toString(StandardView view);

struct CameraSettings {
  StandardView view = StandardView::Anterior;
  double azimuthDeg = 0.0;
  double elevationDeg = 0.0;
  double rollDeg = 0.0;
  double zoom = 1.0;
  glm::dvec2 panMm{0.0};
  bool perspective = false;
  double fovDeg = 30.0;  // vertical, perspective only
  // The image shape (width / height) the zoom was chosen for (issue 36 item 4); <= 0: the
  // image's own. In an image of another shape the picture shows at least the field that the
  // zoom shows in that shape (the whole rectangle, with more around it on one side): a zoom
  // set for a portrait whole body keeps the body whole in a landscape pane or a square image.
  double fitAspect = 0.0;
};

struct Camera {
  glm::dvec3 eye{0.0};      // world position (perspective) or a point on the view plane
  glm::dvec3 forward{0.0};  // unit line of sight
  glm::dvec3 up{0.0};       // unit, screen up
  glm::dvec3 right{0.0};    // unit, screen right
  bool perspective = false;
  double halfHeightMm = 0.0;      // orthographic: half the view height in mm
  double tanHalfFov = 0.0;        // perspective
  double aspect = 1.0;            // width / height
  glm::dmat4 worldFromClip{1.0};  // inverse of projection * view
  glm::dmat4 clipFromWorld{1.0};
};

// The projector through a point of the image, given in normalised device coordinates (-1..1,
// y up): its origin on the near plane and its unit direction, both in world mm. The ray caster
// starts its distances t at this origin.
struct WorldRay {
  glm::dvec3 origin{0.0};
  glm::dvec3 direction{0.0};
};
WorldRay rayThrough(const Camera& camera, const glm::dvec2& ndc);

// The zoom that frames at `imageSize`, without fitAspect, what `settings` frames there.
double fittedZoom(const CameraSettings& settings, glm::ivec2 imageSize);

// A camera that shows a sphere of `radius` mm around `centre` whole at zoom 1.
Camera makeCamera(const CameraSettings& settings, const glm::dvec3& centre, double radius,
                  glm::ivec2 imageSize);

}  // namespace mvw::render
