// libFuzzer: a DIMSE C-FIND response's identifier. The bytes are a dataset as it arrives over
// the association (the first byte picks implicit or explicit VR little endian, the transfer
// syntaxes mvw proposes), read by DCMTK as DcmSCU reads it, then turned into a match by pacs'
// internal matchFromIdentifier (what dimseFind does with each pending response). A dataset
// DCMTK refuses is the association's failure, not passed on; a crash, a sanitizer report or
// any exception is a finding.
#include <cstdint>

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dcdatset.h>
#include <dcmtk/dcmdata/dcistrmb.h>

#include "FuzzInput.h"
#include "Internal.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  mvw::pacs::detail::quietDcmtk();
  const E_TransferSyntax xfer = data[0] & 1 ? EXS_LittleEndianExplicit : EXS_LittleEndianImplicit;
  DcmInputBufferStream stream;
  stream.setBuffer(data + 1, static_cast<offile_off_t>(size - 1));
  stream.setEos();
  DcmDataset identifier;
  identifier.transferInit();
  const OFCondition read = identifier.read(stream, xfer, EGL_noChange, 64 * 1024);
  identifier.transferEnd();
  if (read.bad()) {
    if (const char* v = std::getenv("MVW_FUZZ_VERBOSE"); v && *v == '1')
      std::fprintf(stderr, "refused by DCMTK: %s\n", read.text());
    return 0;
  }
  mvw::fuzz::expectOnly<>([&] { (void)mvw::pacs::detail::matchFromIdentifier(identifier); });
  return 0;
}
