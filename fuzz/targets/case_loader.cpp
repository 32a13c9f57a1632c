// Fuzz target: a case file as palpa-cli validate and the windows load it. Parse and check
// the JSON, build every body (the least-squares fit of its skeleton), then save the case and
// load the saved text again, which must give the same document.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "palpa/io/case_file.hpp"
#include "palpa/scene/scene.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  palpa::io::CaseFile file;
  try {
    file = palpa::io::parse_case(text, "fuzz.json");
    (void)palpa::scene::Scene::build(file, "fuzz.json");
  } catch (const palpa::io::CaseError&) {
    return 0;  // refused with a message naming the field: what a bad case must get
  }
  // Accepted: saving and loading again changes nothing.
  const auto saved = palpa::io::to_json(file);
  const auto again = palpa::io::to_json(palpa::io::parse_case(saved.dump(2), "saved.json"));
  if (again != saved) std::abort();
  return 0;
}
