#pragma once
#include <CLI/App.hpp>

namespace mvw::app {

// `mvw convert INPUT -o OUT.nii.gz|.nii|.mha`: the volume every other command reads, written
// as NIfTI or MetaImage, with a JSON sidecar (OUT.json) saying what it is, as dcm2niix does.
void addConvertCommand(CLI::App& app);

}  // namespace mvw::app
