// Catch2 v2 test runner entry point (Debian's catch2 package).
#define CATCH_CONFIG_MAIN
#include <catch2/catch.hpp>
