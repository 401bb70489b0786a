/*
 * rd_store_check — what the job store's files say at start, before SQLite
 * opens them (rd_store_create calls these; issue 45).
 *
 * The WAL (FILE-wal).  SQLite replays its frames at open up to the first
 * frame whose salt or checksum is wrong and silently drops the rest; frames
 * of the current generation (the header's salt) after that point that end a
 * transaction are commits that are lost.  Frames of an older generation
 * (another salt) after a clean end are stale, not damage.  The format:
 * https://www.sqlite.org/fileformat2.html#walformat (header 32 bytes: magic,
 * version, page size, checkpoint, salt-1, salt-2, checksum-1, checksum-2;
 * frame header 24 bytes: page, db size after commit (0: not a commit),
 * salt-1, salt-2, checksum-1, checksum-2; checksums cumulative over the
 * header's first 24 bytes, then each frame's first 8 bytes and its page, in
 * big-endian 32-bit words when the magic is 0x377f0683, little-endian for
 * 0x377f0682).
 */
#ifndef RD_STORE_CHECK_H
#define RD_STORE_CHECK_H

#include <stddef.h>

#include "rd_error.h"

/* What the WAL of a store file holds. */
typedef struct rd_store_wal {
    long frames;       /* whole frames in the file */
    long commits;      /* commit frames SQLite will replay */
    long lost_commits; /* commit frames of this generation it will drop */
    long first_bad;    /* 1-based frame where replay stops early; 0: none */
    int header_bad;    /* the header is unreadable: every frame is dropped */
} rd_store_wal;

/* Scans FILE-wal (no file or an empty one: all zero, RD_OK).  RD_EINTERNAL
 * only when the file exists but cannot be read. */
int rd_store_wal_scan(const char *file, rd_store_wal *out, rd_error *err);

/* Before SQLite opens FILE: when its WAL would drop commits, copies the WAL
 * to FILE-wal.damaged-<UTC time> and writes one line for the log into
 * `report` (size n; left empty otherwise).  Never fails the start: an
 * unreadable WAL is reported the same way. */
void rd_store_check_wal(const char *file, char *report, size_t n);

/* Moves a damaged store aside: FILE (and FILE-wal) become
 * FILE.damaged-<UTC time> (-wal), FILE-shm is removed, and `report` (size n)
 * gets one line for the log: `why`, where it went, how to recover from it.
 * RD_EINTERNAL when the rename fails (the start is then refused). */
int rd_store_quarantine(const char *file, const char *why, char *report, size_t n, rd_error *err);

#endif
