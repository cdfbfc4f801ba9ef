// libFuzzer: the saved PACS servers file (config::readServerList, servers.json).
#include "FuzzInput.h"
#include "mvw/config/ServerList.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = mvw::fuzz::writeInput(data, size, "servers.json");
  mvw::fuzz::expectInputErrorOnly([&] { (void)mvw::config::readServerList(path); });
  return 0;
}
