// The self-contained OMG IDL text of each recorded type (climbsim/recording/omgidl_schema.hpp).

#include "climbsim/recording/omgidl_schema.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

namespace climbsim::recording {
namespace {

std::size_t at(const std::string& text, const std::string& what) {
  const auto pos = text.find(what);
  EXPECT_NE(pos, std::string::npos) << what << " is not in\n" << text;
  return pos;
}

TEST(OmgidlSchema, HoldsTheTypeAndWhatItUsesFirst) {
  const std::string drive = omgidlSchemaText("climbsim::DriveState");
  EXPECT_EQ(drive.rfind("module climbsim {", 0), 0u) << drive;
  EXPECT_LT(at(drive, "struct WheelState"), at(drive, "struct DriveState"));
  EXPECT_EQ(drive.find("struct RobotState"), std::string::npos) << "a type it does not use";
  EXPECT_EQ(drive.find("//"), std::string::npos) << "comments are left out";
  EXPECT_NE(drive.find("@key string<64> source;"), std::string::npos) << drive;

  const std::string start = omgidlSchemaText("climbsim::RunStart");
  EXPECT_LT(at(start, "struct RosterEntry"), at(start, "struct RunStart"));
  EXPECT_LT(at(start, "struct ParticipantIdentity"), at(start, "struct RunStart"));
  const std::string stop = omgidlSchemaText("climbsim::Stop");
  EXPECT_LT(at(stop, "enum StopKind"), at(stop, "struct Stop"));
}

TEST(OmgidlSchema, EveryRecordedTypeHasOne) {
  for (const char* type : {"climbsim::ChamberState", "climbsim::AdhesionForce", "climbsim::Leakage",
                           "climbsim::RobotState", "climbsim::DriveState", "climbsim::DepthGrid",
                           "climbsim::RunStart", "climbsim::Stop"}) {
    const std::string text = omgidlSchemaText(type);
    const std::string name = std::string(type).substr(10);
    EXPECT_NE(text.find("struct " + name + " {"), std::string::npos) << type << ":\n" << text;
    EXPECT_EQ(text.substr(text.size() - 3), "};\n") << type;
  }
}

TEST(OmgidlSchema, TypedefsConstantsAndModulesResolve) {
  const std::vector<IdlText> files = {
      {"a.idl", "#include \"b.idl\"\nmodule m {\n  const long N = 4; // four\n  typedef double Vec[N];\n"
                "  /* a\n block */ struct Unused { long x; };\n  struct P { Vec v; };\n};\n"},
      {"b.idl", "module m {\n  @final\n  struct Q {\n    P p; sequence<P, N> ps;\n  };\n};\nmodule other { struct Q { long y; }; };\n"}};
  const std::string q = omgidlSchemaText(files, "m::Q");
  EXPECT_LT(at(q, "const long N = 4;"), at(q, "typedef double Vec[N];"));
  EXPECT_LT(at(q, "typedef double Vec[N];"), at(q, "struct P {"));
  EXPECT_LT(at(q, "struct P {"), at(q, "struct Q {"));
  EXPECT_EQ(q.find("Unused"), std::string::npos);
  EXPECT_EQ(q.find("long y"), std::string::npos) << "the other module's Q";
  EXPECT_EQ(q.find('#'), std::string::npos);
  EXPECT_EQ(q.find("block"), std::string::npos);
  EXPECT_EQ(omgidlSchemaText(files, "other::Q"), "module other {\n struct Q { long y; };\n};\n");
}

TEST(OmgidlSchema, AnUnknownTypeOrAnOpenModuleIsAnError) {
  EXPECT_THROW(omgidlSchemaText("climbsim::NoSuchType"), std::invalid_argument);
  EXPECT_THROW(omgidlSchemaText({{"c.idl", "module m { struct S { long x; };\n"}}, "m::S"), std::invalid_argument);
}

}  // namespace
}  // namespace climbsim::recording
