// Fixed ray budget: the total matches the budget within 1 % for random gaze and budgets.
#include "core/rng.h"
#include "foveation/spp_model.h"
#include "gaze/gaze_source.h"
#include "test_support.h"

using namespace fovrt;

TEST_CASE("Ray budget within 1% for every model, random gaze and budgets", "[foveation]") {
    const int w = 64, h = 48;
    const int64_t n = int64_t(w) * h;
    EyeCamera cam(Pose(), Fov::FromHorizontal(Radians(100.0f), float(w) / h), w, h);
    Pcg32 rng(1234);
    for (const char* name : {"disc", "linear", "acuity", "uniform"}) {
        for (int trial = 0; trial < 25; ++trial) {
            FoveationParams p;
            p.model = name;
            p.radiusPx = 400.0f;  // a visible disc at 64 px wide
            p.uniformSpp = 2;
            p.rayBudget = n + int64_t(rng.NextBounded(uint32_t(15 * n)));
            auto model = CreateSppModel(p);
            REQUIRE(model->Name() == std::string("budget(") + name + ")");
            vec3 gaze = GazeDirectionFromAngles(rng.NextFloat() * 80 - 40, rng.NextFloat() * 60 - 30);
            Plane<uint16_t> spp;
            model->Generate(cam, gaze, uint32_t(trial), spp);
            int64_t total = 0;
            for (size_t i = 0; i < spp.size(); ++i) {
                REQUIRE(spp[i] >= 1);
                REQUIRE(spp[i] <= kMaxSpp);
                total += spp[i];
            }
            INFO(name << " budget " << p.rayBudget << " total " << total);
            REQUIRE(std::abs(double(total - p.rayBudget)) <= 0.01 * double(p.rayBudget));
            // The stronger guarantee of the implementation: within 2 samples.
            CHECK(std::abs(double(total - p.rayBudget)) <= 2.0);
        }
    }
}

TEST_CASE("Ray budget keeps the foveation shape and is deterministic", "[foveation]") {
    const int w = 64, h = 64;
    EyeCamera cam(Pose(), Fov::FromHorizontal(Radians(90.0f), 1.0f), w, h);
    FoveationParams p;  // disc: 8 inside / 1 outside
    p.radiusPx = 300.0f;  // 15 px at 64 wide
    p.rayBudget = 3 * w * h;
    auto model = CreateSppModel(p);
    Plane<uint16_t> a, b, c;
    model->Generate(cam, vec3(0, 0, -1), 5, a);
    model->Generate(cam, vec3(0, 0, -1), 5, b);
    model->Generate(cam, vec3(0, 0, -1), 6, c);
    CHECK(a.vector() == b.vector());
    double inside = 0, outside = 0;
    int nIn = 0, nOut = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            double dx = x + 0.5 - 32, dy = y + 0.5 - 32;
            if (dx * dx + dy * dy <= 14 * 14) inside += a(x, y), ++nIn;
            else if (dx * dx + dy * dy > 16 * 16) outside += a(x, y), ++nOut;
        }
    CHECK(inside / nIn > 3.0 * outside / nOut);
    int64_t totalC = 0;
    for (size_t i = 0; i < c.size(); ++i) totalC += c[i];
    CHECK(std::abs(totalC - p.rayBudget) <= 2);

    // Infeasible budgets clamp to [spp_floor*W*H, spp_cap*W*H].
    p.rayBudget = 10;
    CreateSppModel(p)->Generate(cam, vec3(0, 0, -1), 0, a);
    for (size_t i = 0; i < a.size(); ++i) REQUIRE(a[i] == 1);
    p.rayBudget = 100 * w * h;
    CreateSppModel(p)->Generate(cam, vec3(0, 0, -1), 0, a);
    for (size_t i = 0; i < a.size(); ++i) REQUIRE(a[i] == p.sppCap);
}

TEST_CASE("A raised spp_cap lets a budget's fovea past 16 and no pixel past the cap", "[foveation]") {
    const int w = 64, h = 48;
    const int64_t n = int64_t(w) * h;
    EyeCamera cam(Pose(), Fov::FromHorizontal(Radians(100.0f), float(w) / h), w, h);
    FoveationParams p;
    p.model = "linear";  // 8 spp inside 5°, 1 beyond 30°: scaled ×4 by a 4-spp budget
    p.sppMin = 0.25f;
    p.sppFloor = 0.0625f;
    p.rayBudget = 4 * n;
    const auto largest = [&](int cap, int64_t& total) {
        p.sppCap = cap;
        Plane<uint16_t> spp;
        CreateSppModel(p)->Generate(cam, vec3(0, 0, -1), 3, spp);
        uint16_t top = 0;
        total = 0;
        for (size_t i = 0; i < spp.size(); ++i) top = std::max(top, spp[i]), total += spp[i];
        return top;
    };
    int64_t total16 = 0, total48 = 0, totalMax = 0;
    CHECK(largest(16, total16) == 16);  // the default cap binds: the fovea wants more
    const uint16_t top48 = largest(48, total48);
    CHECK(top48 > 16);
    CHECK(top48 <= 48);
    CHECK(largest(kMaxSpp, totalMax) <= kMaxSpp);
    // The same budget either way (the masked periphery meets it in expectation: within 2 %).
    for (int64_t total : {total16, total48, totalMax}) CHECK(std::abs(double(total - p.rayBudget)) <= 0.02 * double(n * 4));
    // Every budget up to spp_cap × W·H is feasible: at the cap, every pixel holds it.
    p.rayBudget = 48 * n;
    CHECK(largest(48, total48) == 48);
    CHECK(total48 == 48 * n);
}

TEST_CASE("spp_cap_ratio makes the cap follow the budget's mean", "[foveation]") {
    const int w = 64, h = 48;
    const int64_t n = int64_t(w) * h;
    EyeCamera cam(Pose(), Fov::FromHorizontal(Radians(100.0f), float(w) / h), w, h);
    FoveationParams p;
    p.model = "linear";  // 64 spp inside 5°, 1/16 beyond 30°: the fovea wants more than the cap
    p.sppMax = 64;
    p.sppMin = 0.0625f;
    p.sppFloor = 0.0625f;
    p.sppCapRatio = 4;
    // Closed forms: ⌈4 × mean⌉, at most kMaxSpp; the ratio off leaves spp_cap.
    for (const auto& [budget, cap] : std::vector<std::pair<int64_t, int>>{
             {n, 4}, {2 * n, 8}, {6 * n, 24}, {n / 2, 2}, {n + n / 3, 6}, {20 * n, kMaxSpp}}) {
        p.rayBudget = budget;
        INFO("budget " << budget << " over " << n << " pixels");
        CHECK(BudgetSppCap(p, n) == cap);
        Plane<uint16_t> spp;
        CreateSppModel(p)->Generate(cam, vec3(0, 0, -1), 3, spp);
        uint16_t top = 0;
        int64_t total = 0;
        for (size_t i = 0; i < spp.size(); ++i) top = std::max(top, spp[i]), total += spp[i];
        CHECK(top == cap);  // the steep map fills its fovea to the cap, and no pixel passes it
        CHECK(std::abs(double(total - budget)) <= 0.02 * double(budget));
    }
    // A mean rounded up to whole samples keeps its cap: 1.75 spp over 3073 pixels is 5377.75,
    // set as 5378, 4 × 5378 / 3073 = 7.0003.
    p.rayBudget = std::llround(1.75 * 3073);
    CHECK(BudgetSppCap(p, 3073) == 7);
    p.sppCapRatio = 0;
    p.rayBudget = 2 * n;
    CHECK(BudgetSppCap(p, n) == p.sppCap);
    // Below 1 the cap would sit below the mean and make the budget infeasible: refused.
    p.sppCapRatio = 0.5f;
    CHECK_THROWS_WITH(CreateSppModel(p), Catch::Contains("foveation.spp_cap_ratio"));
}

TEST_CASE("A uniform map's budget is not bounded by the cap", "[foveation]") {
    // The cap bounds a shaped map's peak; uniform sampling's pixels all sit at the mean, so a sweep
    // can anchor on uniform at 32 spp with the default cap of 16.
    const int w = 40, h = 30;
    const int64_t n = int64_t(w) * h;
    EyeCamera cam(Pose(), Fov::FromHorizontal(Radians(100.0f), float(w) / h), w, h);
    FoveationParams p;
    p.model = "uniform";
    p.sppFloor = 0.0625f;
    p.rayBudget = 32 * n;
    REQUIRE(p.sppCap == 16);
    CHECK(FlatSppMap(p));
    CHECK(BudgetSppCap(p, n) == 32);
    Plane<uint16_t> spp;
    CreateSppModel(p)->Generate(cam, vec3(0, 0, -1), 5, spp);
    for (size_t i = 0; i < spp.size(); ++i) REQUIRE(spp[i] == 32);
    // Below the cap nothing changes, and past kMaxSpp the budget stays infeasible.
    p.rayBudget = 8 * n;
    CHECK(BudgetSppCap(p, n) == 16);
    p.rayBudget = 80 * n;
    CHECK(BudgetSppCap(p, n) == kMaxSpp);
    // A shaped map keeps the cap it was given.
    p.model = "linear";
    p.rayBudget = 32 * n;
    CHECK_FALSE(FlatSppMap(p));
    CHECK(BudgetSppCap(p, n) == 16);
}
