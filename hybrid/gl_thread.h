#pragma once
// A thread that owns a headless GL context (GL contexts live on one thread) and runs submitted
// tasks on it, in submission order. Used by the pass scheduler for the GL splatter; the future
// viewer's window context is a different one, on its own (main) thread.
#include <condition_variable>
#include <deque>
#include <functional>
#include <future>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <type_traits>

#include "gpu/gl_context.h"

namespace tyndall {

class GlThread {
public:
    /// Starts the thread and creates the context on it; throws Error with GlContext::create's
    /// reason when there is none (the thread is gone by then).
    explicit GlThread(GlBackend backend = GlBackend::Auto);
    /// Runs the tasks still queued, destroys the context on its thread and joins.
    ~GlThread();
    GlThread(const GlThread&) = delete;
    GlThread& operator=(const GlThread&) = delete;

    const std::string& description() const { return m_description; }
    bool isSoftware() const { return m_software; }

    /// Queues f(GlContext&) for the GL thread; the future holds its result or its exception.
    template <class F>
    auto submit(F f) -> std::future<std::invoke_result_t<F, GlContext&>> {
        using R = std::invoke_result_t<F, GlContext&>;
        auto task = std::make_shared<std::packaged_task<R(GlContext&)>>(std::move(f));
        std::future<R> result = task->get_future();
        enqueue([task](GlContext& ctx) { (*task)(ctx); });
        return result;
    }

private:
    void enqueue(std::function<void(GlContext&)> task);
    void loop(GlBackend backend, std::promise<void>& started);

    std::mutex m_mutex;
    std::condition_variable m_wake;
    std::deque<std::function<void(GlContext&)>> m_tasks;
    bool m_stop = false;
    std::string m_description;
    bool m_software = false;
    std::thread m_thread;
};

}  // namespace tyndall
