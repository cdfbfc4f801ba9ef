// render_volume VOLUME OUT.png: one headless volume rendering of a DICOM series, NIfTI or
// MetaImage file, through the installed mvw package (mvw::io reads, mvw::render renders).
#include <exception>
#include <iostream>

#include "mvw/core/Error.h"
#include "mvw/io/Png.h"
#include "mvw/io/VolumeReader.h"
#include "mvw/render/GlContext.h"
#include "mvw/render/VolumeRenderer.h"

int main(int argc, char** argv) {
  if (argc != 3) {
    std::cerr << "usage: " << argv[0] << " VOLUME OUT.png\n";
    return 2;
  }
  try {
    const mvw::Volume volume = mvw::io::readVolume(argv[1]);  // LPS mm, physical units

    // Headless OSMesa context; the renderer sizes its own render target.
    auto context = mvw::render::createHeadlessContext({16, 16});
    mvw::render::VolumeRenderer renderer(*context, volume);

    mvw::render::RenderSettings settings;  // composite DVR, shading on
    settings.size = {321, 243};            // odd on purpose
    settings.transfer = mvw::render::transferPreset("ct-bone");
    settings.camera.view = mvw::render::StandardView::Anterior;
    settings.camera.azimuthDeg = 25.0;
    const mvw::render::RenderedFrame frame = renderer.render(settings);

    mvw::io::writePng(frame.image, argv[2]);
    std::cout << "rendered " << frame.image.width << " x " << frame.image.height << " in "
              << frame.milliseconds << " ms on " << context->renderer() << "\n";
    return 0;
  } catch (const mvw::InputError& e) {  // bad input: exit 2, as the mvw CLI does
    std::cerr << "error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "internal error: " << e.what() << "\n";
    return 1;
  }
}
