// Fuzz target: the byte stream from a Novint Falcon. The input is cut into reads of the
// sizes its first bytes give and fed to the packet reader; every packet it returns must
// encode back to a well-formed packet that decodes to the same words.
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "palpa/device/falcon_packet.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace palpa::device::falcon;
  if (size < 2) return 0;
  const std::size_t chunk = 1 + data[0] % 64;  // USB reads of any size
  PacketReader reader;
  std::uint64_t packets = 0;
  for (std::size_t at = 1; at < size; at += chunk) {
    reader.feed(data + at, std::min(chunk, size - at));
    Words words;
    while (reader.next(words)) {
      ++packets;
      Packet packet{};
      encode(words, packet);
      Words again;
      if (decode(packet.data(), again) != nullptr) std::abort();
      if (again.value != words.value || again.flags != words.flags) std::abort();
    }
  }
  // Every byte fed is in one packet returned, skipped (bad frames are skipped byte by byte
  // as the reader resynchronises), or still buffered: never counted twice.
  if (packets * kPacketSize + reader.skipped_bytes() > size - 1) std::abort();
  return 0;
}
