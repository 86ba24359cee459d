// Placeholder: the bridge is being written (issue 5).
#include "rugo/box2d.hpp"
