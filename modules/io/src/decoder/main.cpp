// mvw-decoder: compressed DICOM pixel data decoded in a process of its own, for mvw_io
// (IsolatedDecoder.h), which starts it. Nothing else.
#include "IsolatedDecoder.h"

int main(int argc, char** argv) { return mvw::io::detail::decoderMain(argc, argv); }
