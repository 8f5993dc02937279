"""Physical constants used throughout rockscreen."""

#: Acceleration of gravity [m/s^2]. The rocking literature this project reproduces
#: (Housner 1963; Makris and co-authors; Newmark 1965) uses 9.81.
G = 9.81
