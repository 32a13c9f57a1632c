#include "palpa/device/falcon_packet.hpp"

#include <cstring>

namespace palpa::device::falcon {

namespace {
constexpr std::uint8_t kStart = '<', kEnd = '>', kOffset = 0x41;
}

void encode(const Words& words, Packet& packet) {
  packet[0] = kStart;
  for (std::size_t w = 0; w < 3; ++w) {
    const auto bits = static_cast<std::uint16_t>(words.value[w]);
    for (std::size_t n = 0; n < 4; ++n) {
      packet[1 + 4 * w + n] = static_cast<std::uint8_t>(((bits >> (4 * n)) & 0x0F) + kOffset);
    }
  }
  packet[13] = static_cast<std::uint8_t>(words.flags + kOffset);
  packet[14] = kOffset;
  packet[15] = kEnd;
}

const char* decode(const std::uint8_t* packet, Words& words) {
  if (packet[0] != kStart) return "no '<' at byte 0";
  if (packet[15] != kEnd) return "no '>' at byte 15";
  Words out;
  for (std::size_t w = 0; w < 3; ++w) {
    std::uint16_t bits = 0;
    for (std::size_t n = 0; n < 4; ++n) {
      const std::uint8_t b = packet[1 + 4 * w + n];
      if (b < kOffset || b > kOffset + 0x0F) return "a word byte is not a nibble ('A'..'P')";
      bits = static_cast<std::uint16_t>(bits | ((b - kOffset) << (4 * n)));
    }
    out.value[w] = static_cast<std::int16_t>(bits);  // two's complement: the sign comes with the cast
  }
  if (packet[13] < kOffset || packet[13] > kOffset + 0x7F) return "the flags byte is out of range";
  out.flags = static_cast<std::uint8_t>(packet[13] - kOffset);
  words = out;
  return nullptr;
}

void PacketReader::feed(const std::uint8_t* data, std::size_t size) {
  // Keep the newest bytes if a reader stalls: old packets are worthless at 1 kHz.
  if (size > buffer_.size()) {
    skipped_ += size - buffer_.size();
    data += size - buffer_.size();
    size = buffer_.size();
  }
  if (size_ + size > buffer_.size()) {
    const std::size_t drop = size_ + size - buffer_.size();
    std::memmove(buffer_.data(), buffer_.data() + drop, size_ - drop);
    size_ -= drop;
    skipped_ += drop;
  }
  std::memcpy(buffer_.data() + size_, data, size);
  size_ += size;
}

bool PacketReader::next(Words& words) {
  std::size_t start = 0;
  bool found = false;
  while (!found) {
    while (start < size_ && buffer_[start] != kStart) ++start;
    if (size_ - start < kPacketSize) break;
    if (buffer_[start + kPacketSize - 1] != kEnd || decode(buffer_.data() + start, words) != nullptr) {
      ++bad_;
      ++start;  // resynchronise on the next '<'
      continue;
    }
    found = true;
  }
  const std::size_t consumed = found ? start + kPacketSize : start;
  skipped_ += start;  // bytes before the packet (or before a partial one)
  std::memmove(buffer_.data(), buffer_.data() + consumed, size_ - consumed);
  size_ -= consumed;
  return found;
}

}  // namespace palpa::device::falcon
