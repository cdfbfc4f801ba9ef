#pragma once
// The one thread that makes every GL call of the module (mvw.Study): a GL context is current on
// one thread at a time, and EGL refuses one current elsewhere. Python threads hand it their work
// and wait with the GIL released; so renders from several Python threads are serialised, and each
// context lives, renders and dies on the thread that made it.
#include <functional>

namespace mvw::python {

// Runs `work` on the GL thread and returns when it is done; its exception is rethrown here.
// Call it with the GIL released (work must not touch Python objects).
void onGlThread(const std::function<void()>& work);

}  // namespace mvw::python
