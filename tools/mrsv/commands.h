// The subcommands of mrsv. Each takes the arguments after its name.
#pragma once

namespace mrsv::cli {

int runEncode(int argc, char** argv);
int runDecode(int argc, char** argv);
int runInfo(int argc, char** argv);
int runCheck(int argc, char** argv);

}  // namespace mrsv::cli
