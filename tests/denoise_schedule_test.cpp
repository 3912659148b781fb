// The schedule rules every backend shares (denoise/schedule.h): the feedback iteration and the
// ping-pong plane that holds the filtered illumination.
#include <catch2/catch.hpp>

#include "denoise/schedule.h"

using namespace fovrt;

TEST_CASE(
    "feedback iteration: SVGF keeps the configured one, two-history feeds back iteration 1 at the "
    "latest") {
    SvgfParams p;
    p.atrousIterations = 5;
    p.feedbackIteration = 2;  // Falcor's choice
    CHECK(FeedbackIteration(p, false) == 2);
    CHECK(FeedbackIteration(p, true) == 1);
    p.feedbackIteration = 0;  // the unfiltered accumulation
    CHECK(FeedbackIteration(p, false) == 0);
    CHECK(FeedbackIteration(p, true) == 0);
    p.feedbackIteration = 1;
    p.atrousIterations = 0;  // no à-trous: nothing filtered to feed back
    CHECK(FeedbackIteration(p, false) == 0);
    CHECK(FeedbackIteration(p, true) == 0);
}

TEST_CASE(
    "filtered illumination plane follows the ping-pong: reprojection 0, moments 1, iteration i "
    "writes i&1") {
    CHECK(FilteredIlluminationPlane(0) == 1);  // the variance estimate's output
    CHECK(FilteredIlluminationPlane(1) == 0);
    CHECK(FilteredIlluminationPlane(2) == 1);
    CHECK(FilteredIlluminationPlane(5) == 0);  // the paper's 5 iterations
}
