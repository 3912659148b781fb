// KeyQueue: a live window's key presses, in order. They arrive through GLFW's key callback (a
// press shorter than one poll would be missed by polling glfwGetKey), and the window loop takes
// them one by one. Create it before the ImGui layer: ImGui's backend chains to the callback it
// finds installed.
#pragma once

#include <deque>
#include <optional>

struct GLFWwindow;

namespace fovrt {

class KeyQueue {
public:
    // Installs the key callback (and the window's user pointer, which points here); the
    // destructor removes both, so a window that outlives the queue never calls into it.
    explicit KeyQueue(GLFWwindow* window);
    ~KeyQueue();
    KeyQueue(const KeyQueue&) = delete;
    KeyQueue& operator=(const KeyQueue&) = delete;

    bool Empty() const { return keys_.empty(); }
    // The oldest press not yet taken, or nullopt.
    std::optional<int> Pop();

private:
    static void OnKey(GLFWwindow* window, int key, int scancode, int action, int mods);
    GLFWwindow* window_;
    std::deque<int> keys_;
};

}  // namespace fovrt
