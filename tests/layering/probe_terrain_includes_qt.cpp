// Must not compile: the domain libraries use no Qt.
#include <QString>
