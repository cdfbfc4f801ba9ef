#pragma once
// The picture for checking a registration by eye (registration_qa.png of mvw register).
//
// Three orthogonal world planes through the centre of the fixed (anatomical) volume, in
// columns: axial (patient's right on the image's left, anterior up), coronal (right on the
// left, superior up) and sagittal (anterior on the left, superior up). Rows: the moving
// (functional) volume in a colour map over the grey anatomy before registration, the same
// after, then checkerboards of anatomy and functional (each in grey, 16-pixel tiles) before
// and after: edges that continue across the tiles mean the volumes are aligned.
#include "mvw/core/Image.h"
#include "mvw/core/Volume.h"
#include "mvw/resampling/Transform.h"

namespace mvw::resampling {

struct RegistrationQaOptions {
  int panelPixels = 256;      // the longest side of a panel
  double overlayAlpha = 0.6;  // opacity of the hottest functional voxels
};

// `before`, `after`: fixedFromMoving transforms (anatomicalFromFunctional), as resample takes.
Image registrationQaImage(const Volume& fixed, const Volume& moving, const Transform& before,
                          const Transform& after, const RegistrationQaOptions& options = {});

}  // namespace mvw::resampling
