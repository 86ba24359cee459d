/* placeholder */ namespace { int placeholder; }
