// OMPL's own steering lengths per second, on benches/steer.rs's pairs: the
// other side of issue 23's steering target (scripts/bench_ompl_steer.sh
// builds and runs it beside `cargo bench --bench steer`).
//
// The 10,000 pairs are the bench's: scen's SplitMix64 with seed 5, starts and
// goals uniform in [-10, 10]^2 with headings uniform in [-pi, pi), turning
// radius 1. Prints, per state space, the sum of the lengths over one pass
// (the same pairs give the same sum in scen, to rounding) and the rate.
//
// Usage: ompl_steer [PASSES]   (default 100)
#include <ompl/base/spaces/DubinsStateSpace.h>
#include <ompl/base/spaces/ReedsSheppStateSpace.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <vector>

namespace ob = ompl::base;

// scen::rng::SplitMix64, number for number.
struct SplitMix64 {
    uint64_t state;
    uint64_t next_u64() {
        state += 0x9E3779B97F4A7C15ULL;
        uint64_t z = state;
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
        return z ^ (z >> 31);
    }
    double range(double lo, double hi) {
        double u = double(next_u64() >> 11) * (1.0 / double(uint64_t(1) << 53));
        return lo + (hi - lo) * u;
    }
};

int main(int argc, char** argv) {
    const int passes = argc > 1 ? std::atoi(argv[1]) : 100;
    const int pairs = 10000;
    for (int model = 0; model < 2; ++model) {
        ob::StateSpacePtr space = model == 0
            ? ob::StateSpacePtr(std::make_shared<ob::ReedsSheppStateSpace>(1.0))
            : ob::StateSpacePtr(std::make_shared<ob::DubinsStateSpace>(1.0));
        SplitMix64 rng{5};
        std::vector<ob::State*> from(pairs), to(pairs);
        auto pose = [&](ob::State* s) {
            auto* se2 = s->as<ob::SE2StateSpace::StateType>();
            double x = rng.range(-10.0, 10.0), y = rng.range(-10.0, 10.0);
            se2->setXY(x, y);
            se2->setYaw(rng.range(-M_PI, M_PI));
        };
        for (int i = 0; i < pairs; ++i) {
            from[i] = space->allocState();
            to[i] = space->allocState();
            pose(from[i]);
            pose(to[i]);
        }
        double sum = 0.0;
        auto start = std::chrono::steady_clock::now();
        for (int p = 0; p < passes; ++p)
            for (int i = 0; i < pairs; ++i) sum += space->distance(from[i], to[i]);
        double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        std::printf("ompl %-11s lengths of one pass %.6f  %.3f M/s  (%.2f us a length)\n",
                    model == 0 ? "reeds_shepp" : "dubins", sum / passes, passes * pairs / secs / 1e6,
                    secs / (passes * double(pairs)) * 1e6);
        for (int i = 0; i < pairs; ++i) {
            space->freeState(from[i]);
            space->freeState(to[i]);
        }
    }
    return 0;
}
