#include "hot_journal.hpp"

#include <array>
#include <cstdint>
#include <fstream>
#include <string>

namespace palpa::session::detail {
namespace {

constexpr std::array<unsigned char, 8> kJournalMagic{0xd9, 0xd5, 0x05, 0xf9, 0x20, 0xa1, 0x63, 0xd7};

std::uint32_t big_endian_u32(const unsigned char* p) {
  return (std::uint32_t{p[0]} << 24) | (std::uint32_t{p[1]} << 16) | (std::uint32_t{p[2]} << 8) | std::uint32_t{p[3]};
}

}  // namespace

JournalBeside journal_beside(const std::filesystem::path& file) {
  auto journal = file;
  journal += "-journal";
  std::ifstream in(journal, std::ios::binary);
  if (!in) return JournalBeside::None;
  // Header: magic, record count, checksum nonce, initial page count, sector size, page size.
  std::array<unsigned char, 28> header{};
  in.read(reinterpret_cast<char*>(header.data()), static_cast<std::streamsize>(header.size()));
  if (in.gcount() != static_cast<std::streamsize>(header.size())) return JournalBeside::None;
  for (std::size_t k = 0; k < kJournalMagic.size(); ++k) {
    if (header[k] != kJournalMagic[k]) return JournalBeside::None;
  }
  const std::uint32_t records = big_endian_u32(&header[8]);
  const std::uint32_t sector = big_endian_u32(&header[20]);
  const std::uint32_t page = big_endian_u32(&header[24]);
  std::error_code ec;
  const auto size = std::filesystem::file_size(journal, ec);
  if (ec || sector < 32 || sector > 65536 || page < 512 || page > 65536) return JournalBeside::Transaction;
  const std::uint64_t record_bytes = 4ull + page + 4ull;
  // 0xFFFFFFFF: the count was never written; the records fill the rest of the file.
  const std::uint64_t count = records == 0xFFFFFFFFu ? (size > sector ? (size - sector) / record_bytes : 0) : records;
  if (count == 0) return JournalBeside::None;  // nothing to roll back
  if (count != 1 || size < sector + record_bytes) return JournalBeside::Transaction;
  std::array<unsigned char, 4> first{};
  in.seekg(static_cast<std::streamoff>(sector));
  in.read(reinterpret_cast<char*>(first.data()), static_cast<std::streamsize>(first.size()));
  if (in.gcount() != 4) return JournalBeside::Transaction;
  return big_endian_u32(first.data()) == 1 ? JournalBeside::HeaderSwitchOnly : JournalBeside::Transaction;
}

std::string sqlite_uri(const std::filesystem::path& path, const char* query) {
  static constexpr char kHex[] = "0123456789ABCDEF";
  std::string uri = "file:";
  for (const char ch : std::filesystem::absolute(path).string()) {
    const auto c = static_cast<unsigned char>(ch);
    const bool plain = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '/' ||
                       c == '-' || c == '_' || c == '.' || c == '~';
    if (plain) {
      uri += static_cast<char>(c);
    } else {
      uri += '%';
      uri += kHex[c >> 4];
      uri += kHex[c & 0xF];
    }
  }
  uri += '?';
  uri += query;
  return uri;
}

}  // namespace palpa::session::detail
