# The libFuzzer harnesses (tests/fuzz/fuzz_TARGET.cpp), built as fuzz_TARGET by the fuzz preset
# (tests/fuzz/CMakeLists.txt) and as fuzz_seeds_TARGET with the plain seed driver by every test
# build (tests/CMakeLists.txt). Keep in step with FUZZ_TARGETS in tests/fuzz/seeds.
set(MVW_FUZZ_TARGETS nifti metaimage dicom config csa png seg multipart qido cfind servers manifest
                     script)

# What one harness needs beyond mvw::io and mvw::config: the internal parsers are behind their
# module's src/ folder (a detail:: entry point in its Internal.h or own header).
function(mvw_fuzz_target_needs exe target)
  if(target STREQUAL "csa")
    target_include_directories(${exe} PRIVATE ${CMAKE_SOURCE_DIR}/modules/io/src)
  elseif(target MATCHES "^(multipart|qido|cfind)$")
    target_include_directories(${exe} PRIVATE ${CMAKE_SOURCE_DIR}/modules/pacs/src)
    target_link_libraries(${exe} PRIVATE mvw::pacs)
    if(target STREQUAL "cfind")
      target_link_libraries(${exe} PRIVATE DCMTK::dcmdata DCMTK::ofstd)
    endif()
  elseif(target STREQUAL "manifest")
    target_link_libraries(${exe} PRIVATE mvw::batch)
  elseif(target STREQUAL "script")
    target_link_libraries(${exe} PRIVATE mvw::viewer)
  endif()
endfunction()
