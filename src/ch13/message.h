/* message.h: errors on standard error, with every byte a terminal could
 * obey escaped (chapter 1). */
#ifndef MESSAGE_H
#define MESSAGE_H

/* text on stderr, with every byte a terminal could obey shown as \xHH. */
void message_print_escaped(const char *text);

/* "NAME: error: MESSAGE", or with ":LINE:COL" after NAME when line > 0. */
void message_print_error(const char *name, int line, int col,
                         const char *message);

/* "NAME: warning: MESSAGE": valid input that is most likely a mistake. */
void message_print_warning(const char *name, const char *message);

#endif
