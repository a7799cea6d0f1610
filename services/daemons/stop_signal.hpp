#pragma once
// SIGINT and SIGTERM ask a daemon's main loop to finish (close the bus, flush the store); a
// second signal is not caught again, so it ends a daemon that hangs.
namespace ambid::daemons {

void install_stop_handlers();
bool stop_requested();

}  // namespace ambid::daemons
