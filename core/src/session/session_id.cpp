#include "palpa/session/session_id.hpp"

#include <algorithm>
#include <random>

namespace palpa::session {

std::string new_session_id() {
  static constexpr char kHex[] = "0123456789abcdef";
  std::random_device device;
  std::string id;
  for (int k = 0; k < 4; ++k) {
    auto word = device();
    for (int d = 0; d < 8; ++d, word >>= 4) id += kHex[word & 0xF];
  }
  return id;
}

bool is_session_id(std::string_view id) {
  const auto hex = [](char c) { return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'); };
  return (id.size() == 32 || id.size() == 16) && std::all_of(id.begin(), id.end(), hex);
}

}  // namespace palpa::session
