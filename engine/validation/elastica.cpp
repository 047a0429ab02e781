#include "engine/validation/case.h"
