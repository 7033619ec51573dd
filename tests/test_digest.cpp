// The digest stored in every compressed file: short, and read back within what the decoder checks it with.
#include "symcompress/verify.hpp"

#include <catch2/catch.hpp>

using namespace symcompress;

TEST_CASE("The digest is short and reads back within a millionth of the diagonal, far from the origin too",
          "[verify]") {
    TriangleMesh mesh;
    mesh.positions = {{1e5 + 0.123456789, -2e5, 3.3}, {1e5 + 1.987654321, -2e5 + 0.5, 3.3}, {1e5, -2e5, 4.0123456789}};
    mesh.triangles = {{0, 1, 2}};
    SurfaceDigest digest = digestOf(mesh, 0);
    digest.maxError = 5e-5;
    const std::string text = digest.json();
    CHECK(text.size() < 110);
    SurfaceDigest back;
    REQUIRE(SurfaceDigest::fromJson(text, back));
    CHECK(back.triangles == 1);
    CHECK(back.area == Approx(digest.area).epsilon(1e-6));
    CHECK(back.maxError == 5e-5);
    const double diagonal = digest.bounds.diagonal().norm();
    CHECK((back.bounds.min() - digest.bounds.min()).cwiseAbs().maxCoeff() <= 1e-6 * diagonal);
    CHECK((back.bounds.max() - digest.bounds.max()).cwiseAbs().maxCoeff() <= 1e-6 * diagonal);
    CHECK(back.poseError == 0);
    // With an allowance of its own for the poses (--animation-error): one number more, read back.
    digest.poseError = 5e-5 + 1e-3;
    SurfaceDigest posed;
    REQUIRE(SurfaceDigest::fromJson(digest.json(), posed));
    CHECK(posed.poseError == Approx(1.05e-3));
    CHECK(posed.maxError == 5e-5);
    CHECK(posed.bounds.isApprox(back.bounds));
    digest.bounds.setEmpty();
    REQUIRE(SurfaceDigest::fromJson(digest.json(), posed));
    CHECK(posed.poseError == Approx(1.05e-3));
}

TEST_CASE("The digest's older object form is still read, and a malformed one is not", "[verify]") {
    SurfaceDigest back;
    REQUIRE(SurfaceDigest::fromJson(R"({"symcompress_digest":{"area":2.5,"bbox":{"max":[1,2,3],"min":[0,0,0]},)"
                                    R"("max_error":5e-05,"triangles":7}})",
                                    back));
    CHECK(back.triangles == 7);
    CHECK(back.area == 2.5);
    CHECK(back.maxError == 5e-5);
    CHECK(back.bounds.max() == Eigen::Vector3d(1, 2, 3));
    CHECK_FALSE(SurfaceDigest::fromJson(R"({"symcompress_digest":[7,2.5,5e-05]})", back));
    CHECK_FALSE(SurfaceDigest::fromJson(R"({"symcompress_digest":[7,"x",5e-05,0]})", back));
    CHECK_FALSE(SurfaceDigest::fromJson(R"({"other":1})", back));
}
