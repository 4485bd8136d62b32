#include "hybrid/gl_thread.h"

namespace tyndall {

GlThread::GlThread(GlBackend backend) {
    std::promise<void> started;
    std::future<void> ready = started.get_future();
    m_thread = std::thread([this, backend, &started] { loop(backend, started); });
    try {
        ready.get();
    } catch (...) {
        m_thread.join();
        throw;
    }
}

GlThread::~GlThread() {
    {
        std::lock_guard<std::mutex> lock(m_mutex);
        m_stop = true;
    }
    m_wake.notify_all();
    m_thread.join();
}

void GlThread::enqueue(std::function<void(GlContext&)> task) {
    {
        std::lock_guard<std::mutex> lock(m_mutex);
        m_tasks.push_back(std::move(task));
    }
    m_wake.notify_all();
}

void GlThread::loop(GlBackend backend, std::promise<void>& started) {
    std::unique_ptr<GlContext> context;
    try {
        context = GlContext::create(backend);
        m_description = context->description();
        m_software = context->isSoftware();
    } catch (...) {
        started.set_exception(std::current_exception());
        return;
    }
    started.set_value();  // `started` lives on the constructor's stack: not touched after this
    for (;;) {
        std::function<void(GlContext&)> task;
        {
            std::unique_lock<std::mutex> lock(m_mutex);
            m_wake.wait(lock, [&] { return m_stop || !m_tasks.empty(); });
            if (m_tasks.empty()) break;  // stopping, and everything queued has run
            task = std::move(m_tasks.front());
            m_tasks.pop_front();
        }
        task(*context);  // packaged tasks keep their exceptions for the future
    }
}

}  // namespace tyndall
