// Case files: every validation rule, preservation of unknown fields, hostile input.
#include "palpa/io/case_file.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <functional>
#include <random>

#include <unistd.h>

#include "palpa/mat/layer_stiffness.hpp"
#include "palpa/mat/mat_body.hpp"

namespace palpa::io {
namespace {

using nlohmann::json;

// A valid 3 x 4 body on z = 0 with radius only at the two interior points.
json base_case() {
  json body = {{"id", "b0"}, {"rows", 3}, {"cols", 4}};
  json medial = json::array();
  json radius = json::array();
  json stiffness = json::array();
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 4; ++j) {
      medial.push_back({0.01 * j, 0.01 * i, 0.0});
      radius.push_back(i == 1 && (j == 1 || j == 2) ? 0.004 : 0.0);
      stiffness.push_back(200.0);
    }
  }
  body["medial"] = medial;
  body["radius"] = radius;
  body["stiffness"] = stiffness;
  return {{"format", "palpa-case"}, {"version", 1}, {"title", "base"}, {"bodies", json::array({body})}};
}

// The first problem of a case, or "" if it is valid.
Problem first_problem(const std::string& text) {
  try {
    (void)parse_case(text, "case.json");
  } catch (const CaseError& e) {
    EXPECT_EQ(e.file(), "case.json");
    EXPECT_FALSE(e.problems().empty());
    return e.problems().front();
  }
  return {"", ""};
}

Problem problem_after(const std::function<void(json&)>& mutate) {
  json doc = base_case();
  mutate(doc);
  return first_problem(doc.dump());
}

// The base case's body given by its Young's modulus (5 kPa) instead of its stiffness.
void by_modulus(json& d) {
  d["bodies"][0].erase("stiffness");
  d["bodies"][0]["modulus"] = std::vector<double>(12, 5000.0);
}

struct Rule {
  const char* name;
  std::function<void(json&)> mutate;
  const char* where;
  const char* keyword;
};

void PrintTo(const Rule& rule, std::ostream* os) { *os << rule.name; }

class Validation : public ::testing::TestWithParam<Rule> {};

TEST_P(Validation, NamesThePlaceAndTheReason) {
  const auto& rule = GetParam();
  const auto p = problem_after(rule.mutate);
  EXPECT_EQ(p.where, rule.where) << rule.name << ": " << p.reason;
  EXPECT_NE(p.reason.find(rule.keyword), std::string::npos) << rule.name << ": " << p.reason;
}

const Rule kRules[] = {
    {"wrong format", [](json& d) { d["format"] = "stl"; }, "/format", "format"},
    {"missing format", [](json& d) { d.erase("format"); }, "/", "format"},
    {"version 2", [](json& d) { d["version"] = 2; }, "/version", "version"},
    {"version string", [](json& d) { d["version"] = "1"; }, "/version", "version"},
    {"title not string", [](json& d) { d["title"] = 5; }, "/title", "string"},
    {"no bodies", [](json& d) { d["bodies"] = json::array(); }, "/bodies", "non-empty"},
    {"body not object", [](json& d) { d["bodies"][0] = 3; }, "/bodies/0", "object"},
    {"missing id", [](json& d) { d["bodies"][0].erase("id"); }, "/bodies/0", "id"},
    {"empty id", [](json& d) { d["bodies"][0]["id"] = ""; }, "/bodies/0/id", "non-empty"},
    {"rows fraction", [](json& d) { d["bodies"][0]["rows"] = 3.5; }, "/bodies/0/rows", "integer"},
    {"rows as string", [](json& d) { d["bodies"][0]["rows"] = "3"; }, "/bodies/0/rows", "integer"},
    {"grid 1 x N", [](json& d) { d["bodies"][0]["rows"] = 1; }, "/bodies/0/rows", "outside [2, 256]"},
    {"absurd grid", [](json& d) { d["bodies"][0]["rows"] = 100000; d["bodies"][0]["cols"] = 100000; },
     "/bodies/0/rows", "outside"},
    {"huge integer", [](json& d) { d["bodies"][0]["cols"] = 18446744073709551615ull; }, "/bodies/0/cols", "outside"},
    {"negative cols", [](json& d) { d["bodies"][0]["cols"] = -4; }, "/bodies/0/cols", "outside"},
    {"count mismatch", [](json& d) { d["bodies"][0]["radius"].erase(0); }, "/bodies/0/radius", "expected rows*cols"},
    {"medial not triplets", [](json& d) { d["bodies"][0]["medial"][5] = {0.01, 0.01}; }, "/bodies/0/medial/5", "3 numbers"},
    {"coordinate string", [](json& d) { d["bodies"][0]["medial"][5][2] = "0"; }, "/bodies/0/medial/5/2", "number"},
    {"coordinate too far", [](json& d) { d["bodies"][0]["medial"][5][0] = 1e5; }, "/bodies/0/medial/5/0", "outside"},
    {"negative radius", [](json& d) { d["bodies"][0]["radius"][5] = -0.001; }, "/bodies/0/radius/5", "negative radius"},
    {"radius too large", [](json& d) { d["bodies"][0]["radius"][5] = 11.0; }, "/bodies/0/radius/5", "outside"},
    {"boundary radius", [](json& d) { d["bodies"][0]["radius"][0] = 0.001; }, "/bodies/0/radius/0", "boundary"},
    {"negative stiffness", [](json& d) { d["bodies"][0]["stiffness"][3] = -1.0; }, "/bodies/0/stiffness/3", "negative stiffness"},
    {"stiffness bool", [](json& d) { d["bodies"][0]["stiffness"][3] = true; }, "/bodies/0/stiffness/3", "number"},
    {"missing stiffness", [](json& d) { d["bodies"][0].erase("stiffness"); }, "/bodies/0", "stiffness"},
    {"stiffness and modulus", [](json& d) { d["bodies"][0]["modulus"] = std::vector<double>(12, 5000.0); },
     "/bodies/0/modulus", "not both"},
    {"negative modulus", [](json& d) { by_modulus(d); d["bodies"][0]["modulus"][3] = -1.0; }, "/bodies/0/modulus/3", "negative modulus"},
    {"modulus count", [](json& d) { by_modulus(d); d["bodies"][0]["modulus"].erase(0); }, "/bodies/0/modulus", "expected rows*cols"},
    {"poisson one half", [](json& d) { by_modulus(d); d["bodies"][0]["poisson"] = 0.5; }, "/bodies/0/poisson", "outside"},
    {"poisson string", [](json& d) { by_modulus(d); d["bodies"][0]["poisson"] = "0.45"; }, "/bodies/0/poisson", "number"},
    {"force model typo", [](json& d) { d["bodies"][0]["force_model"] = "calibrate"; }, "/bodies/0/force_model", "\"calibrated\""},
    {"negative damping", [](json& d) { d["bodies"][0]["damping"] = json::array(); for (int k = 0; k < 12; ++k) d["bodies"][0]["damping"].push_back(k == 7 ? -0.1 : 0.1); },
     "/bodies/0/damping/7", "negative damping"},
    {"zero mass", [](json& d) { d["bodies"][0]["mass"] = json::array(); for (int k = 0; k < 12; ++k) d["bodies"][0]["mass"].push_back(k == 2 ? 0.0 : 1e-3); },
     "/bodies/0/mass/2", "outside (0"},
    {"coincident neighbours", [](json& d) { d["bodies"][0]["medial"][6] = d["bodies"][0]["medial"][5]; },
     "/bodies/0/medial/6", "coincides"},
    {"duplicate ids", [](json& d) { d["bodies"].push_back(d["bodies"][0]); }, "/bodies/1/id", "duplicate"},
    {"tumors not array", [](json& d) { d["tumors"] = json::object(); }, "/tumors", "array"},
    {"tumour not object", [](json& d) { d["tumors"] = json::array({1}); }, "/tumors/0", "object"},
    {"root not object", [](json& d) { d = json::array(); }, "/", "object"},
    {"id with newline", [](json& d) { d["bodies"][0]["id"] = "b\n0"; }, "/bodies/0/id", "control"},
    // Not plausible bodies (CaseLimits: at most 2 m across, 0.5 m thick, points 0.5 m apart).
    {"a body 198 m wide", [](json& d) { for (std::size_t k = 0; k < 12; ++k) d["bodies"][0]["medial"][k][0] = -99.0 + 66.0 * static_cast<double>(k % 4); },
     "/bodies/0/medial", "not a plausible body: its skeleton spans 198 m along x"},
    {"a point pulled 1.5 m out", [](json& d) { d["bodies"][0]["medial"][11] = {1.5, 0.02, 0.0}; },
     "/bodies/0/medial/7", "not a plausible body: a neighbouring skeleton point"},
    {"a body 0.6 m thick", [](json& d) { d["bodies"][0]["radius"][5] = 0.3; },
     "/bodies/0/radius/5", "not a plausible body: radius 0.3 m makes it 0.6 m thick"},
    {"interior pole row", [](json& d) { for (std::size_t j = 0; j < 4; ++j) d["bodies"][0]["medial"][4 + j] = {0.015, 0.01, 0.0}; },
     "/bodies/0/medial/5", "coincides"},
};

INSTANTIATE_TEST_SUITE_P(Rules, Validation, ::testing::ValuesIn(kRules),
                         [](const auto& test_info) {
                           std::string n = test_info.param.name;
                           for (auto& c : n) if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return n;
                         });

TEST(CaseFile, AModulusGivesTheStiffnessOfTheLocalLayerUnderAFingertip) {
  json doc = base_case();
  by_modulus(doc);
  const auto file = parse_case(doc.dump(), "kpa.json");
  const auto& g = file.bodies[0];
  ASSERT_EQ(g.stiffness.size(), 12u);
  EXPECT_EQ(g.poisson, 0.49);
  EXPECT_EQ(g.force_model, mat::ForceModel::Calibrated);
  for (std::size_t k = 0; k < 12; ++k) {
    // k = 2 a E kappa(a / h) / (1 - nu^2) over the local thickness h = 2R (at least the pad radius).
    EXPECT_NEAR(g.stiffness[k] / mat::layer_stiffness(5000.0, 0.49, mat::kFingertipPadRadius, 2.0 * g.radius[k]), 1.0,
                1e-6) << k;
  }
  // Saved as authored: the modulus, not the derived stiffness; no default written out.
  const json saved = to_json(file);
  EXPECT_FALSE(saved["bodies"][0].contains("stiffness"));
  EXPECT_EQ(saved["bodies"][0]["modulus"], doc["bodies"][0]["modulus"]);
  EXPECT_FALSE(saved["bodies"][0].contains("force_model"));
  EXPECT_FALSE(saved["bodies"][0].contains("poisson"));
  EXPECT_EQ(parse_case(saved.dump(), "again.json").bodies[0].stiffness, g.stiffness);
}

TEST(CaseFile, ForceModelAndPoissonAreKeptWhereGiven) {
  json doc = base_case();
  EXPECT_EQ(parse_case(doc.dump(), "n.json").bodies[0].force_model, mat::ForceModel::Paper) << "N/m: the paper's law";
  doc["bodies"][0]["force_model"] = "calibrated";
  EXPECT_EQ(parse_case(doc.dump(), "n.json").bodies[0].force_model, mat::ForceModel::Calibrated);
  by_modulus(doc);
  doc["bodies"][0]["force_model"] = "paper";
  doc["bodies"][0]["poisson"] = 0.45;
  const auto file = parse_case(doc.dump(), "kpa.json");
  EXPECT_EQ(file.bodies[0].force_model, mat::ForceModel::Paper);
  EXPECT_EQ(file.bodies[0].poisson, 0.45);
  const json saved = to_json(file);
  EXPECT_EQ(saved["bodies"][0]["force_model"], "paper");
  EXPECT_EQ(saved["bodies"][0]["poisson"], 0.45);
  // A more compressible tissue is softer under the pad.
  json nu49 = base_case();
  by_modulus(nu49);
  EXPECT_LT(file.bodies[0].stiffness[5], parse_case(nu49.dump(), "nu49.json").bodies[0].stiffness[5]);
}

TEST(CaseFile, BaseCaseIsValidAndFits) {
  const auto file = parse_case(base_case().dump(), "case.json");
  ASSERT_EQ(file.bodies.size(), 1u);
  EXPECT_EQ(file.bodies[0].rows, 3);
  EXPECT_EQ(file.bodies[0].medial[5][0], 0.01);
  EXPECT_NO_THROW((void)mat::MatBody::fit(file.bodies[0]));
}

TEST(CaseFile, APoleRowMayCoincideWithinItself) {
  json doc = base_case();
  for (std::size_t j = 0; j < 4; ++j) doc["bodies"][0]["medial"][j] = {0.015, 0.0, 0.0};  // row 0 collapses to a point
  EXPECT_EQ(first_problem(doc.dump()).reason, "");
  // ...but two whole rows on the same point are coincident neighbours.
  for (std::size_t j = 0; j < 4; ++j) doc["bodies"][0]["medial"][4 + j] = {0.015, 0.0, 0.0};
  EXPECT_NE(first_problem(doc.dump()).reason.find("coincides"), std::string::npos);
}

TEST(CaseFile, IntegralFloatsCountAsIntegers) {
  json doc = base_case();
  doc["bodies"][0]["rows"] = 3.0;  // JSON Schema's "integer" accepts 3.0 too
  EXPECT_EQ(first_problem(doc.dump()).reason, "");
}

TEST(CaseFile, ErrorLinesStayShortWhateverTheInput) {
  json doc = base_case();
  doc["version"] = json::array();
  for (int k = 0; k < 100000; ++k) doc["version"].push_back(k);
  const auto p = first_problem(doc.dump());
  EXPECT_EQ(p.where, "/version");
  EXPECT_LT(p.reason.size(), 120u) << p.reason;
}

TEST(CaseFile, TooManyValuesAreRejectedBeforeParsing) {
  std::string many = "{\"x\": [";
  for (std::size_t k = 0; k < CaseLimits::kMaxValues + 10; ++k) many += "[],";
  many += "[]]}";
  const auto p = first_problem(many);
  EXPECT_NE(p.reason.find("more than"), std::string::npos) << p.reason;
}

TEST(CaseFile, SyntaxErrorsGiveLineAndColumn) {
  const auto p = first_problem("{\n  \"format\": \"palpa-case\",\n  \"version\": 1,,\n}");
  EXPECT_EQ(p.where, "line 3, column 16");
  EXPECT_NE(p.reason.find("not JSON"), std::string::npos);
  EXPECT_NE(first_problem("").reason.find("not JSON"), std::string::npos);
  EXPECT_NE(first_problem("{\"a\": 1e400}").reason.find("overflow"), std::string::npos);
}

TEST(CaseFile, DeepNestingIsRejectedBeforeParsing) {
  std::string deep = "{\"format\": \"palpa-case\", \"x\": " + std::string(100000, '[') + std::string(100000, ']') + "}";
  const auto p = first_problem(deep);
  EXPECT_NE(p.reason.find("nesting"), std::string::npos) << p.reason;
  // Brackets inside strings do not count.
  json doc = base_case();
  doc["comment"] = std::string(1000, '[');
  EXPECT_EQ(first_problem(doc.dump()).reason, "");
}

TEST(CaseFile, ManyProblemsAreCappedAndCounted) {
  json doc = base_case();
  for (auto& k : doc["bodies"][0]["stiffness"]) k = -1.0;
  doc["bodies"].push_back(doc["bodies"][0]);
  doc["bodies"][1]["id"] = "b1";
  try {
    (void)parse_case(doc.dump(), "many.json");
    FAIL();
  } catch (const CaseError& e) {
    EXPECT_EQ(e.problems().size(), CaseLimits::kMaxProblems + 1);
    EXPECT_NE(e.problems().back().reason.find("more problems"), std::string::npos);
    EXPECT_EQ(e.lines().front().rfind("many.json: /bodies/0/stiffness/0: ", 0), 0u) << e.lines().front();
  }
}

TEST(CaseFile, UnknownFieldsSurviveSaveAndLoad) {
  json doc = base_case();
  doc["author"] = "instructor@example.org";
  doc["bodies"][0]["comment"] = {{"tissue", "fat"}};
  doc["tumors"] = json::array({{{"body", "b0"}, {"center", {0.01, 0.01, 0.0}}, {"radius", 0.002}, {"stiffness", 900.0},
                                {"label", "T1"}}});
  auto file = parse_case(doc.dump(), "in.json");
  file.bodies[0].stiffness[0] = 321.0;  // an edit
  const auto path = std::filesystem::temp_directory_path() /
                    ("palpa-roundtrip-" + std::to_string(::getpid()) + ".json");
  save_case(file, path);
  const auto again = load_case(path);
  EXPECT_EQ(again.document["author"], "instructor@example.org");
  EXPECT_EQ(again.document["bodies"][0]["comment"]["tissue"], "fat");
  EXPECT_EQ(again.document["tumors"][0]["label"], "T1");
  EXPECT_EQ(again.bodies[0].stiffness[0], 321.0);
  EXPECT_EQ(again.bodies[0].medial, file.bodies[0].medial);  // doubles round-trip exactly
  EXPECT_FALSE(std::filesystem::exists(path.string() + ".tmp"));
  std::filesystem::remove(path);
}

TEST(CaseFile, LengthLimitsCountCharactersNotBytes) {
  json doc = base_case();
  std::string title;
  for (int k = 0; k < 1024; ++k) title += "\u00e9";  // 1024 characters, 2048 bytes of UTF-8
  doc["title"] = title;
  EXPECT_EQ(first_problem(doc.dump()).reason, "");
  doc["title"] = title + "e";
  EXPECT_EQ(first_problem(doc.dump()).where, "/title");
}

TEST(CaseFile, MissingFileAndFolderAreClearErrors) {
  try {
    (void)load_case("/nonexistent/case.json");
    FAIL();
  } catch (const CaseError& e) {
    EXPECT_EQ(e.lines().front(), "/nonexistent/case.json: file: no such file");
  }
  EXPECT_THROW((void)load_case(std::filesystem::temp_directory_path()), CaseError);
}

TEST(CaseFile, RandomCorruptionNeverCrashesOrYieldsNaN) {
  // Byte-level mutations of a valid case: each is either rejected with a CaseError or
  // loads into a body that fits to finite surfaces (or is refused by the fit).
  const std::string text = base_case().dump(1);
  std::mt19937 rng(11);
  const std::string alphabet = "{}[],:\"0123456789.-eE tfnul";
  int accepted = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    std::string s = text;
    const int edits = 1 + static_cast<int>(rng() % 4);
    for (int e = 0; e < edits; ++e) {
      const auto pos = rng() % s.size();
      switch (rng() % 3) {
        case 0: s[pos] = alphabet[rng() % alphabet.size()]; break;
        case 1: s.erase(pos, 1 + rng() % 8); break;
        default: s.insert(pos, 1, alphabet[rng() % alphabet.size()]); break;
      }
      if (s.empty()) s = "{";
    }
    try {
      const auto file = parse_case(s, "fuzz.json");
      for (const auto& b : file.bodies) {
        try {
          const auto body = mat::MatBody::fit(b);
          for (double c : body.top().control()) ASSERT_TRUE(std::isfinite(c));
          ++accepted;
        } catch (const mat::FitError&) {
        }
      }
    } catch (const CaseError& e) {
      ASSERT_FALSE(e.lines().empty());
    }
  }
  EXPECT_GT(accepted, 0);  // some mutations (e.g. of digits) are still valid cases
}

}  // namespace
}  // namespace palpa::io
