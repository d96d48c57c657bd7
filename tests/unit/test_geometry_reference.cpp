// Signed distances against two references: values the independent checker
// (shared/tools/check_solution.py, body_sd) printed for random body pairs,
// which must match bit for bit, and a brute-force support-function search
// over many directions, which must agree within its sampling error.
#include <doctest/doctest.h>

#include <algorithm>
#include <limits>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "earc/geometry/shapes.hpp"

using earc::geo::Body;
using earc::geo::CoreKind;
using earc::geo::Vec2;

namespace {

struct CheckerCase {
  Body a;
  Body b;
  double sd;  // check_solution.body_sd(a, b), printed with float.hex()
};

// Two pairs of every kind combination, apart and overlapping, plus a
// near-parallel segment pair; generated with seed 3 by a throw-away script
// that called check_solution.body_sd.
const CheckerCase kCheckerCases[] = {
    {Body::disc({0x1.7b750916a5368p-2, -0x1.7a727250a54f4p+0}, 0x1.d4f6b7e6a6a03p-1),
     Body::box({0x1.4b2b8e218cff8p-2, 0x1.b0892206bdf40p-2}, {0x1.a700aab67eeaep-1, 0x1.2684d97f29ef3p-2}, 0x1.a2a14a6b322fcp+1),
     0x1.5ff6976b59a67p-1},
    {Body::box({0x1.588959c65a506p+0, -0x1.836dd4d2ab1c0p-4}, {0x1.d1c8b04d54534p-3, 0x1.638554891cd9cp+0}, 0x1.921fb54442d18p-1),
     Body::capsule({0x1.ee157403e0a80p-1, 0x1.5f0cfac6f8da0p-1}, {0x1.5aadd387b37dep+1, 0x1.6e03db6d29e20p+0}, 0x0.0p+0),
     0x1.c267c792c3250p-5},
    {Body::capsule({-0x1.be7a9b3df3f80p-4, 0x1.c026c1eb8f624p-1}, {0x1.338ba3d91b58fp+0, -0x1.59619d2614804p-2}, 0x1.9471495d333b4p-3),
     Body::disc({0x1.83f59f2ec9592p+0, -0x1.9c34effb68112p+0}, 0x0.0p+0),
     0x1.1d14e0122d264p+0},
    {Body::box({-0x1.057b22712a818p-2, 0x1.03602ddaf0104p-1}, {0x1.285864b71b2ecp-1, 0x1.0d7fcf33461e0p-1}, -0x1.977f93942f9c8p+0),
     Body::box({-0x1.7a91bad4dcf30p-2, -0x1.1209478c431dep+0}, {0x1.602dbb236e678p-5, 0x1.ad98e4fe451f7p-2}, -0x1.4e4e2551699e8p+0),
     0x1.ae74d96d0410ap-1},
    {Body::box({-0x1.58fc69a693c16p+0, 0x1.714af729c7282p+0}, {0x1.b5131689fdc46p-1, 0x1.121b117f76ebep+0}, 0x1.dbc8bd4558960p+1),
     Body::disc({0x1.1055abd4e441cp-1, 0x1.f3c927c969820p+0}, 0x0.0p+0),
     0x1.0023446822c45p+0},
    {Body::box({0x1.f58fb53de39d4p+0, -0x1.a55b8353f52e2p+0}, {0x1.cf26b707ba66ep-3, 0x1.c36abd9202df2p-2}, 0x1.33cf428886be0p+1),
     Body::capsule({0x1.7db6a38f38ae0p+0, -0x1.d2bfd7328fbd4p+0}, {0x1.6847ba3c03610p+0, -0x1.e5edcd13ef6eap+0}, 0x1.52e5a4c6824ccp-3),
     -0x1.4823d60cb9b7fp-3},
    {Body::disc({-0x1.85cbb4fe25ff0p-1, -0x1.b12e97722925ap+0}, 0x0.0p+0),
     Body::disc({0x1.e2be31b437404p+0, -0x1.aac71e63b86d4p-1}, 0x0.0p+0),
     0x1.6432826bb3d94p+1},
    {Body::capsule({-0x1.7d466ca3ca284p-1, 0x1.d5aad111b4aaep+0}, {0x1.0824be6bac940p-6, 0x1.4665513fd5302p+0}, 0x0.0p+0),
     Body::box({0x1.e43b87f86646ep+0, 0x1.3efd02c0e6412p+0}, {0x1.12cc71cb68110p+0, 0x1.6797651e73c16p+0}, -0x1.d46055919d6e4p+0),
     0x1.a9af546a5a4c8p-2},
    {Body::capsule({0x1.5a264a6c87aa0p-4, 0x1.8cbe0d5b0ab70p-3}, {0x1.1ead4f8b81783p+0, 0x1.1307a014377eep-2}, 0x0.0p+0),
     Body::disc({0x1.1179aba0996d4p-1, -0x1.57240388a3d00p-1}, 0x1.6962c656f2b14p-2),
     0x1.15157beb7da28p-1},
    {Body::capsule({0x1.e77e857d500f4p-1, -0x1.e948ffb48f4bcp+0}, {0x1.42a30f9268997p+1, -0x1.482627c0646c6p+0}, 0x1.012632d0614cap-3),
     Body::capsule({0x1.7b958133f1dd8p-2, -0x1.709687d294894p-1}, {-0x1.2af941aa56ee0p-3, -0x1.110c1b5d5c178p-3}, 0x1.30f54d50e79fep-2),
     0x1.cdfc732b69e25p-1},
    {Body::box({-0x1.a7ce0f3e07396p+0, 0x1.15df9f5c05700p-7}, {0x1.0dca566509598p-1, 0x1.f0d4644567b1ep-1}, -0x1.790b63d7cc1e4p+0),
     Body::box({-0x1.912a77a3a0584p-1, -0x1.e16c22cf15404p-1}, {0x1.8804aa55526c2p-3, 0x1.56f9825ebbf00p-8}, 0x1.f3bc3caa15578p+1),
     0x1.85834ef8a6c24p-2},
    {Body::disc({-0x1.dadc3a807b080p+0, 0x1.11d62a482544ap+0}, 0x0.0p+0),
     Body::disc({0x1.be27e2fef0a90p-3, -0x1.99b049086042ep+0}, 0x1.1b4cb483e9b5ap-1),
     0x1.69d57b54c22d0p+1},
    {Body::box({-0x1.d47168c0b7be8p-1, 0x1.904601c4d6b88p-1}, {0x1.6ae58aa35c3a5p+0, 0x1.583e0233fbdb8p-1}, 0x1.e26245aa6e940p-4),
     Body::disc({-0x1.2d4adb8082b24p-1, 0x1.6335797f70f00p+0}, 0x1.cb49c04d9c3b0p-4),
     -0x1.c53022de5052cp-3},
    {Body::disc({0x1.796a0c2004ef4p+0, -0x1.0b0f3e37e4f00p-1}, 0x1.2c0cba03d9e7cp-2),
     Body::capsule({0x1.cc1b466841ea6p+0, -0x1.dea1fb5e3c218p-2}, {0x1.b1293ef751e0cp-2, -0x1.e814ab190fac0p-1}, 0x1.f4364961dc6b7p-2),
     -0x1.7329254b45b6ap-1},
    {Body::box({-0x1.04f627c234360p-4, 0x1.9f2fd461874a0p-2}, {0x1.671c539e7084dp-2, 0x1.09e4c92489f00p-2}, 0x1.921fb54442d18p-1),
     Body::box({-0x1.434f5b3451b70p-3, -0x1.39ebcd9be2726p+0}, {0x1.639a386f01894p+0, 0x1.6b8b6635529a6p+0}, 0x1.921fb54442d18p-1),
     -0x1.09ee25b3dc6dcp-1},
    {Body::capsule({0x1.dec10ac507e00p-7, 0x1.17ff7d07091a0p-1}, {0x1.f97e6ddd97d0dp-1, 0x1.b794d74110824p+0}, 0x0.0p+0),
     Body::capsule({-0x1.a9cba2ba83d70p-3, -0x1.79e281ef2fbe0p-2}, {-0x1.f24bfe997853ap-3, -0x1.f79ee03792270p-2}, 0x0.0p+0),
     0x1.e294e40879abbp-1},
    {Body::box({0x1.5fe7156692720p+0, 0x1.2398090e7301cp-1}, {0x1.5986ca8cc76f8p-1, 0x1.58684cc9b36d5p+0}, 0x1.839e5c4e5c6e4p+1),
     Body::box({0x1.2c37ef556e1f4p-1, 0x1.fcde7faf5f35ap+0}, {0x1.03f1f9169d26cp-1, 0x1.de3134152533ep-2}, 0x0.0p+0),
     -0x1.27762d20df1e8p-2},
    {Body::box({-0x1.bb633ab272e00p+0, 0x1.324439b69d340p-4}, {0x1.7ff7c7016fa84p-4, 0x1.6ab63d92b823bp-2}, -0x1.001edc53214e4p+1),
     Body::capsule({-0x1.a9cad05fe12c6p+0, -0x1.20e24d56a066ap+0}, {-0x1.f36365a336c00p-2, 0x1.c2a446587dba8p-1}, 0x1.bfdb77b808213p-2),
     -0x1.0e6abeec13598p-3},
    {Body::capsule({0x1.cd9d213ec7900p-7, -0x1.c1292aae2d03ep+0}, {-0x1.dd54cbcfa1d5ep-2, -0x1.ac63926b3e025p+0}, 0x0.0p+0),
     Body::capsule({0x1.cd9d213ec7900p-7, -0x1.c1292aae2d03ep+0}, {-0x1.dd54cbd0d2dfbp-2, -0x1.ac63926b3e025p+0}, 0x1.d122dc1a4f24ap-2),
     -0x1.d122dc1a4f24ap-2},
    {Body::disc({-0x1.e1f3b5c90413cp+0, -0x1.d9ca10afae996p+0}, 0x0.0p+0),
     Body::box({-0x1.02b08785f2c32p+0, -0x1.75141f20cfcd8p+0}, {0x1.86c815e80e246p-1, 0x1.3f1a4f0032859p+0}, 0x1.088279ebb260ep+1),
     -0x1.2b3d7de06a472p-2},
    {Body::capsule({-0x1.7bf841f971080p-4, -0x1.305f4aa3df31cp+0}, {-0x1.5afd4c76bca5ap-3, -0x1.107e301755ebdp+0}, 0x1.2b4948831c288p-2),
     Body::disc({-0x1.d54251a3062c0p-2, -0x1.724748e6e5f70p-1}, 0x1.4ee7754b6edfcp-1),
     -0x1.ff4f34d81ad41p-2},
    {Body::capsule({-0x1.3ffeaf663f00cp-1, -0x1.52570d6362600p+0}, {-0x1.852f2794f0aaap-1, -0x1.123dfec3b5386p+0}, 0x1.162098845bce3p-2),
     Body::capsule({0x1.cad86529c4f10p-3, -0x1.eb7de0c1ba388p+0}, {-0x1.6f10b2c3cb098p+0, -0x1.4e4cffc79e910p+0}, 0x0.0p+0),
     -0x1.67208b4fc56c0p-8},
    {Body::disc({-0x1.160a614c3dc12p+0, -0x1.c7b779abae528p-1}, 0x0.0p+0),
     Body::disc({-0x1.b0299fcd4d7d0p-1, -0x1.b1d8414e29108p-1}, 0x1.10d6e87426dfap-1),
     -0x1.2602d890832fcp-2},
    {Body::disc({0x1.3b5dc41159b48p+0, 0x1.0948c758450f0p-3}, 0x1.ba7594260384cp-3),
     Body::disc({0x1.53dff48b91128p+0, -0x1.04c6e2f847600p-5}, 0x0.0p+0),
     -0x1.d18fd115c96a0p-6},
};

// Support function of a body in direction n (unit): max over the body of n.p.
double support(const Body& b, Vec2 n) {
  switch (b.kind) {
    case CoreKind::Point: return dot(n, b.p0) + b.radius;
    case CoreKind::Segment: return std::max(dot(n, b.p0), dot(n, b.p1)) + b.radius;
    case CoreKind::Rect:
      return dot(n, b.p0) + b.half.x * std::abs(dot(n, b.axis)) + b.half.y * std::abs(dot(n, perp(b.axis))) +
             b.radius;
  }
  return 0.0;
}

// For convex A and B the signed distance is -min over unit n of
// h_A(n) + h_B(-n) (the support of A - B): the separating-axis theorem
// over every direction instead of the checker's edge normals.
double bruteForceSignedDistance(const Body& a, const Body& b, const std::vector<Vec2>& directions) {
  double least = std::numeric_limits<double>::infinity();
  for (Vec2 n : directions) least = std::min(least, support(a, n) + support(b, n * -1.0));
  return -least;
}

std::vector<Vec2> evenDirections(int count) {
  std::vector<Vec2> out;
  for (int i = 0; i < count; ++i) {
    const double t = 2.0 * std::numbers::pi * i / count;
    out.push_back({std::cos(t), std::sin(t)});
  }
  return out;
}

// Largest |p| over a body: the Lipschitz constant of its support function.
double reach(const Body& b) {
  switch (b.kind) {
    case CoreKind::Point: return norm(b.p0) + b.radius;
    case CoreKind::Segment: return std::max(norm(b.p0), norm(b.p1)) + b.radius;
    case CoreKind::Rect: return norm(b.p0) + norm(b.half) + b.radius;
  }
  return 0.0;
}

Body randomBody(std::mt19937& rng) {
  std::uniform_real_distribution<double> pos(-1.5, 1.5), size(0.0, 1.2), ang(-4.0, 4.0), rad(0.0, 0.4);
  std::uniform_int_distribution<int> kind(0, 2);
  const Vec2 c{pos(rng), pos(rng)};
  switch (kind(rng)) {
    case 0: return Body::disc(c, rad(rng));
    case 1: {
      const double a = ang(rng), l = 2.0 * size(rng);
      return Body::capsule(c, c + Vec2{std::cos(a), std::sin(a)} * l, rad(rng));
    }
    default: return Body::box(c, {size(rng), size(rng)}, ang(rng));
  }
}

}  // namespace

TEST_CASE("signed distance equals the checker's body_sd bit for bit") {
  for (const CheckerCase& c : kCheckerCases) {
    CAPTURE(c.sd);
    CHECK(earc::geo::signedDistance(c.a, c.b) == c.sd);
  }
}

TEST_CASE("signed distance agrees with a brute-force search over all directions") {
  std::mt19937 rng(20240611);
  constexpr int kDirections = 1 << 16;
  const std::vector<Vec2> directions = evenDirections(kDirections);
  for (int trial = 0; trial < 300; ++trial) {
    const Body a = randomBody(rng);
    const Body b = randomBody(rng);
    const double exact = earc::geo::signedDistance(a, b);
    const double brute = bruteForceSignedDistance(a, b, directions);
    // Sampled directions can only miss the minimum: brute <= exact, short by
    // at most (Lipschitz constant) x (half the angular spacing).
    const double slack = (reach(a) + reach(b)) * std::numbers::pi / kDirections + 1e-12;
    CAPTURE(trial);
    CHECK(brute <= exact + 1e-12);
    CHECK(exact - brute <= slack);
  }
}
