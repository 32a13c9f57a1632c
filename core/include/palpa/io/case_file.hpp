#pragma once
// Case files v1 (docs/case-format.md): JSON in SI units, strict validation, and unknown
// fields preserved from load to save.
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "palpa/mat/body_grid.hpp"
#include "palpa/mat/tumour.hpp"

namespace palpa::io {

/// One problem in a case file: where (a JSON pointer such as /bodies/0/radius/3, "/" for
/// the root, or "line L, column C" for syntax errors) and why.
struct Problem {
  std::string where;
  std::string reason;
};

/// A case file that cannot be used. what() is the first problem's line.
class CaseError : public std::runtime_error {
 public:
  CaseError(std::string file, std::vector<Problem> problems);
  const std::string& file() const { return file_; }
  const std::vector<Problem>& problems() const { return problems_; }
  /// One line per problem: "FILE: WHERE: REASON".
  std::vector<std::string> lines() const;

 private:
  std::string file_;
  std::vector<Problem> problems_;
};

/// Limits checked before anything is allocated from a file's claims.
struct CaseLimits {
  static constexpr std::uintmax_t kMaxFileBytes = 32u << 20;
  static constexpr int kMaxDepth = 64;
  /// About 4 bodies of 256 x 256 points with every channel; keeps the parsed document
  /// of a hostile file to a few hundred MB at most.
  static constexpr std::size_t kMaxValues = 2'000'000;
  static constexpr int kMaxBodies = 256;
  static constexpr int kMinGrid = 2;
  static constexpr int kMaxGrid = 256;
  static constexpr std::size_t kMaxIdLength = 64;
  static constexpr std::size_t kMaxTitleLength = 1024;
  static constexpr std::size_t kMaxDescriptionLength = 16384;  // characters of "description"
  static constexpr double kMaxCoordinate = 100.0;  // m
  static constexpr double kMaxRadius = 10.0;       // m
  static constexpr double kMaxStiffness = 1e9;     // N/m
  static constexpr double kMaxModulus = 1e9;       // Pa (bone is about 1e10; soft tissues 1e2-1e6)
  static constexpr double kMaxPoisson = 0.499;     // below 0.5: the bonded-layer factor needs nu < 1/2
  static constexpr double kMaxStiffening = 20.0;   // b per unit strain: Krouskop's carcinoma is 11
  static constexpr double kMaxDamping = 1e7;       // N s/m
  static constexpr double kMaxMass = 1e3;          // kg
  static constexpr double kMaxTumourRadius = 1.0;  // m
  /// A plausible body (docs/case-format.md, "Plausible bodies"): every anatomy and phantom
  /// with margin. Its skeleton spans at most this along x, y and z (a whole adult torso is
  /// under 0.7 m across)...
  static constexpr double kMaxBodyExtent = 2.0;     // m
  /// ...it is at most this thick (2 x its largest radius; an abdomen is under 0.35 m)...
  static constexpr double kMaxBodyThickness = 0.5;  // m
  /// ...and neighbouring skeleton points lie at most this far apart.
  static constexpr double kMaxPointSpacing = 0.5;   // m
  static constexpr std::size_t kMaxProblems = 20;  // per file; the rest are counted
};

struct CaseFile {
  std::string title;
  std::vector<mat::BodyGrid> bodies;
  std::vector<mat::Tumour> tumours;
  /// "indenter": what presses bodies under the calibrated law (absent: the flat pad).
  mat::Indenter indenter = mat::Indenter::Pad;
  /// The document as loaded: fields Palpa does not know are written back unchanged by
  /// save_case.
  nlohmann::json document = nlohmann::json::object();
};

/// Parses and validates a case; `source` names the file in errors. Throws CaseError.
CaseFile parse_case(std::string_view text, const std::string& source);

/// Reads, parses and validates a case file. Throws CaseError (also when unreadable).
CaseFile load_case(const std::filesystem::path& path);

/// The document to save: `document` with the known fields replaced by the structured ones.
nlohmann::json to_json(const CaseFile& file);

/// Writes the case atomically (a temporary file renamed over the target), so an existing
/// file is never left half-written. Throws std::runtime_error naming the file.
void save_case(const CaseFile& file, const std::filesystem::path& path);

}  // namespace palpa::io
