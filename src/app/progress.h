// A one-line progress bar on an interactive terminal; silent when stderr is not a TTY or CI is set.
#pragma once

#include <chrono>
#include <string>

namespace fovrt {

class Progress {
public:
    Progress(std::string label, int total);
    ~Progress();
    void Step(const std::string& detail = "");  // one unit done
    void Finish();

private:
    std::string label_;
    int total_ = 0;
    int done_ = 0;
    bool enabled_ = false;
    bool finished_ = false;
    std::chrono::steady_clock::time_point start_;
};

}  // namespace fovrt
