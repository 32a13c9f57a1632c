// import_anatomy with a label table held in memory (the instructor window's "Map labels…"):
// the same case as the table it copies, checked as a table file is, refused for a mesh; the
// provenance names the tool that asked.
#include <gtest/gtest.h>

#include "../core/anatomy/analytic_bodies.hpp"
#include "palpa/anatomy/import_error.hpp"
#include "palpa/anatomy_io/anatomy_io.hpp"
#include "palpa/anatomy_io/import_request.hpp"
#include "support.hpp"

namespace palpa::anatomy_io::test {
namespace {

ImportRequest dome_request(const ScratchDir& dir) {
  ImportRequest r;
  r.input = dir / "dome.nrrd";
  write_label_volume(r.input, anatomy::testing::voxelize(anatomy::testing::dome_on_plane(), 2e-3));
  return r;
}

TEST(ImportRequest, InMemoryTableGivesTheSameCaseAsTheTableItCopies) {
  ScratchDir dir;
  ImportRequest by_name = dome_request(dir);
  by_name.labels = "generic";
  ImportRequest in_memory = dome_request(dir);
  in_memory.table = anatomy::builtin_label_table("generic");
  in_memory.table->name = "labels mapped by hand";
  in_memory.tool = "palpa instructor window";
  const ImportedCase a = import_anatomy(by_name), b = import_anatomy(in_memory);
  ASSERT_EQ(a.file.tumours.size(), 1u);
  ASSERT_EQ(b.file.tumours.size(), 1u);
  EXPECT_EQ(a.file.tumours[0].center, b.file.tumours[0].center);
  EXPECT_EQ(a.file.bodies[0].modulus, b.file.bodies[0].modulus);
  EXPECT_EQ(b.file.document["provenance"]["labels"], "labels mapped by hand");
  EXPECT_EQ(b.file.document["provenance"]["tool"], "palpa instructor window");
  EXPECT_EQ(a.file.document["provenance"]["tool"], "palpa-cli import");
  EXPECT_EQ(io::to_json(b.file)["provenance"]["tool"], "palpa instructor window");  // what saving writes
}

TEST(ImportRequest, InMemoryTableIsCheckedAsATableFile) {
  ScratchDir dir;
  ImportRequest r = dome_request(dir);
  r.table = anatomy::builtin_label_table("generic");
  r.table->labels[4].modulus = 0.0;
  try {
    import_anatomy(r);
    FAIL() << "a lesion without a modulus was accepted";
  } catch (const anatomy::ImportError& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.find('\n'), std::string::npos);
    EXPECT_NE(what.find("label 4"), std::string::npos) << what;
  }
  r.table->labels[4].modulus = 20e3;
  r.table->labels[4].name = std::string(anatomy::kMaxLabelNameLength + 1, 'x');
  EXPECT_THROW(import_anatomy(r), anatomy::ImportError);
}

TEST(ImportRequest, MeshRefusesALabelTable) {
  ScratchDir dir;
  ImportRequest r;
  r.input = dir / "skin.stl";
  r.table = anatomy::builtin_label_table("generic");
  r.modulus = 3000.0;
  r.support_plane = std::array<double, 4>{0, 0, 1, 0};
  EXPECT_THROW(import_anatomy(r), anatomy::ImportError);
}

}  // namespace
}  // namespace palpa::anatomy_io::test
