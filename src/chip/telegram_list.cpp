#include "sercon/chip/telegram_list.hpp"

#include "sercon/chip/telegram_list_walk.hpp"

namespace sercon::chip {

template class BasicTelegramList<ListClient>;

}  // namespace sercon::chip
