// The report's viewer: viewer/src/report.js bundled with three.js and OrbitControls (viewer/build.mjs),
// compiled into the library when it is built; empty when it was built without Node.js and npm.
#pragma once

#include <string>

namespace symcompress {

std::string viewerScript();

}  // namespace symcompress
