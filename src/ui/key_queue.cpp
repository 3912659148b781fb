#include "ui/key_queue.h"

#include <GLFW/glfw3.h>

namespace fovrt {

KeyQueue::KeyQueue(GLFWwindow* window) : window_(window) {
    glfwSetWindowUserPointer(window, this);
    glfwSetKeyCallback(window, OnKey);
}

KeyQueue::~KeyQueue() {
    glfwSetKeyCallback(window_, nullptr);
    glfwSetWindowUserPointer(window_, nullptr);
}

std::optional<int> KeyQueue::Pop() {
    if (keys_.empty()) return std::nullopt;
    const int key = keys_.front();
    keys_.pop_front();
    return key;
}

void KeyQueue::OnKey(GLFWwindow* window, int key, int, int action, int) {
    if (action == GLFW_PRESS) static_cast<KeyQueue*>(glfwGetWindowUserPointer(window))->keys_.push_back(key);
}

}  // namespace fovrt
