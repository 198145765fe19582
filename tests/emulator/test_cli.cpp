#include <gtest/gtest.h>

#include <sstream>

#include "emulator/cli.hpp"
