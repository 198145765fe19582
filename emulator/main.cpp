#include <iostream>

#include "emulator/cli.hpp"

int main(int argc, char** argv) { return navemu::run_cli(argc, argv, std::cout, std::cerr); }
