#pragma once
#include <filesystem>
#include <string>

#include <CLI/App.hpp>

namespace mvw::app {

// `mvw render STUDY.json -o DIR`: headless renders of the views the config lists, one PNG
// per view plus render.json (parameters, GL renderer, time per frame, image checksum).
void addRenderCommand(CLI::App& app);

// What `mvw render STUDY -o OUT_DIR [--gl GL]` does, without overrides: every view of the study
// config into `outDir`. `gl` empty: MVW_GL, else auto. `mvw validate` renders its cases so.
void renderStudy(const std::filesystem::path& study, const std::filesystem::path& outDir,
                 const std::string& gl);

}  // namespace mvw::app
