// cpp-httplib (Debian's libcpp-httplib-dev), included after Eigen: httplib pulls in
// <resolv.h>, whose `_res` macro breaks Eigen's headers when they come after it.
#pragma once

#include <Eigen/Core>
#include <httplib.h>
