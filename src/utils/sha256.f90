module superjoin_utils_sha256
  !! SHA-256 (FIPS 180-4) over a stream of bytes, for content keys and
  !! checksums (the condensation library). A sha256_t is fed by update (text,
  !! or the bytes of integer and real arrays) and closed by digest, which
  !! gives the 64 lower-case hexadecimal digits. 32-bit words are held in
  !! 64-bit integers and masked, so that no signed arithmetic overflows.
  use, intrinsic :: iso_fortran_env, only: int8, int32, int64
  use superjoin_kinds, only: wp
  implicit none (type, external)
  private

  integer(int64), parameter :: MASK32 = int(z'FFFFFFFF', int64)
    !! The low 32 bits.
  integer, parameter :: BLOCK_BYTES = 64
    !! Bytes of one message block.
  integer, parameter :: CHUNK = 4096
    !! Array elements turned into bytes at a time.
  integer(int64), parameter :: K(64) = [ &
       int(z'428a2f98', int64), int(z'71374491', int64), int(z'b5c0fbcf', int64), int(z'e9b5dba5', int64), &
       int(z'3956c25b', int64), int(z'59f111f1', int64), int(z'923f82a4', int64), int(z'ab1c5ed5', int64), &
       int(z'd807aa98', int64), int(z'12835b01', int64), int(z'243185be', int64), int(z'550c7dc3', int64), &
       int(z'72be5d74', int64), int(z'80deb1fe', int64), int(z'9bdc06a7', int64), int(z'c19bf174', int64), &
       int(z'e49b69c1', int64), int(z'efbe4786', int64), int(z'0fc19dc6', int64), int(z'240ca1cc', int64), &
       int(z'2de92c6f', int64), int(z'4a7484aa', int64), int(z'5cb0a9dc', int64), int(z'76f988da', int64), &
       int(z'983e5152', int64), int(z'a831c66d', int64), int(z'b00327c8', int64), int(z'bf597fc7', int64), &
       int(z'c6e00bf3', int64), int(z'd5a79147', int64), int(z'06ca6351', int64), int(z'14292967', int64), &
       int(z'27b70a85', int64), int(z'2e1b2138', int64), int(z'4d2c6dfc', int64), int(z'53380d13', int64), &
       int(z'650a7354', int64), int(z'766a0abb', int64), int(z'81c2c92e', int64), int(z'92722c85', int64), &
       int(z'a2bfe8a1', int64), int(z'a81a664b', int64), int(z'c24b8b70', int64), int(z'c76c51a3', int64), &
       int(z'd192e819', int64), int(z'd6990624', int64), int(z'f40e3585', int64), int(z'106aa070', int64), &
       int(z'19a4c116', int64), int(z'1e376c08', int64), int(z'2748774c', int64), int(z'34b0bcb5', int64), &
       int(z'391c0cb3', int64), int(z'4ed8aa4a', int64), int(z'5b9cca4f', int64), int(z'682e6ff3', int64), &
       int(z'748f82ee', int64), int(z'78a5636f', int64), int(z'84c87814', int64), int(z'8cc70208', int64), &
       int(z'90befffa', int64), int(z'a4506ceb', int64), int(z'bef9a3f7', int64), int(z'c67178f2', int64)]
    !! Round constants (fractional parts of the cube roots of the first 64 primes).
  integer(int64), parameter :: H0(8) = [ &
       int(z'6a09e667', int64), int(z'bb67ae85', int64), int(z'3c6ef372', int64), int(z'a54ff53a', int64), &
       int(z'510e527f', int64), int(z'9b05688c', int64), int(z'1f83d9ab', int64), int(z'5be0cd19', int64)]
    !! Initial hash value.
  logical, parameter :: LITTLE_ENDIAN = iachar(transfer(1_int32, 'a')) == 1
    !! Byte order of this machine (a word's first byte is its lowest).

  type, public :: sha256_t
    !! A hash in progress.
     integer(int64) :: h(8) = H0
     character(len=BLOCK_BYTES) :: buf = ''     !! bytes not yet compressed
     integer :: nbuf = 0
     integer(int64) :: length = 0               !! message bytes so far
  end type sha256_t

  interface update
    !! Feed bytes: text, or the storage of an integer or real array.
     module procedure update_text, update_int32, update_int64, update_real64, update_real64_2d
  end interface update

  public :: update, digest, sha256_hex

contains

  function sha256_hex(text) result(hex)
    !! The SHA-256 of text, 64 hexadecimal digits.
    character(*), intent(in) :: text
    character(len=64) :: hex
    type(sha256_t) :: s
    call update(s, text)
    hex = digest(s)
  end function sha256_hex

  subroutine update_text(s, text)
    !! Feed the bytes of text.
    type(sha256_t), intent(inout) :: s
    character(*), intent(in) :: text
    integer :: pos, take
    pos = 1
    s%length = s%length + len(text)
    do while (pos <= len(text))
       if (s%nbuf == 0 .and. len(text) - pos + 1 >= BLOCK_BYTES) then   ! whole blocks straight from text
          call compress(s%h, text(pos:pos + BLOCK_BYTES - 1))
          pos = pos + BLOCK_BYTES
          cycle
       end if
       take = min(BLOCK_BYTES - s%nbuf, len(text) - pos + 1)
       s%buf(s%nbuf + 1:s%nbuf + take) = text(pos:pos + take - 1)
       s%nbuf = s%nbuf + take
       pos = pos + take
       if (s%nbuf == BLOCK_BYTES) then
          call compress(s%h, s%buf)
          s%nbuf = 0
       end if
    end do
  end subroutine update_text

  subroutine update_int32(s, a)
    !! Feed the storage of a default-integer array.
    type(sha256_t), intent(inout) :: s
    integer(int32), intent(in) :: a(:)
    integer :: i, j
    do i = 1, size(a), CHUNK   ! in pieces that stay in cache
       j = min(i + CHUNK - 1, size(a))
       call update_text(s, transfer(a(i:j), repeat(' ', 4*(j - i + 1))))
    end do
  end subroutine update_int32

  subroutine update_int64(s, a)
    !! Feed the storage of an int64 array.
    type(sha256_t), intent(inout) :: s
    integer(int64), intent(in) :: a(:)
    integer :: i, j
    do i = 1, size(a), CHUNK   ! in pieces that stay in cache
       j = min(i + CHUNK - 1, size(a))
       call update_text(s, transfer(a(i:j), repeat(' ', 8*(j - i + 1))))
    end do
  end subroutine update_int64

  subroutine update_real64(s, a)
    !! Feed the storage of a real64 array.
    type(sha256_t), intent(inout) :: s
    real(wp), intent(in) :: a(:)
    integer :: i, j
    do i = 1, size(a), CHUNK   ! in pieces that stay in cache
       j = min(i + CHUNK - 1, size(a))
       call update_text(s, transfer(a(i:j), repeat(' ', 8*(j - i + 1))))
    end do
  end subroutine update_real64

  subroutine update_real64_2d(s, a)
    !! Feed the storage of a real64 matrix (column by column).
    type(sha256_t), intent(inout) :: s
    real(wp), intent(in) :: a(:, :)
    integer :: j
    do j = 1, size(a, 2)
       call update_real64(s, a(:, j))
    end do
  end subroutine update_real64_2d

  function digest(s) result(hex)
    !! Close the hash (padding and length) and give its 64 hexadecimal digits.
    type(sha256_t), intent(in) :: s
    character(len=64) :: hex
    type(sha256_t) :: t
    character(len=8) :: len_bytes
    integer(int64) :: bits
    integer :: i, nib
    character(len=16), parameter :: DIGITS = '0123456789abcdef'
    t = s
    bits = t%length*8
    do i = 1, 8
       len_bytes(i:i) = achar(iand(shiftr(bits, 8*(8 - i)), 255_int64))
    end do
    call update_text(t, transfer(int(-128, int8), 'a'))   ! the byte 0x80
    do while (t%nbuf /= BLOCK_BYTES - 8)
       call update_text(t, achar(0))
    end do
    call update_text(t, len_bytes)
    do i = 1, 64
       nib = int(iand(shiftr(t%h(shiftr(i - 1, 3) + 1), 4*(7 - mod(i - 1, 8))), 15_int64)) + 1
       hex(i:i) = DIGITS(nib:nib)
    end do
  end function digest

  pure integer(int64) function rotr(x, n)
    !! Rotate the 32-bit word x (< 2**32) right by n bits, in the low 32 bits;
    !! the bits above are left over, not cleared: rotr's results only enter
    !! sums and exclusive ors that are masked before a word is stored.
    integer(int64), intent(in) :: x
    integer, intent(in) :: n
    rotr = ior(shiftr(x, n), shiftl(x, 32 - n))
  end function rotr

  pure subroutine compress(h, blk)
    !! One block of the compression function.
    integer(int64), intent(inout) :: h(8)
    character(len=BLOCK_BYTES), intent(in) :: blk
    integer(int64) :: w(64), a(8), s0, s1, ch, maj, t1, t2, x
    integer(int32) :: m(16)
    integer :: i
    m = transfer(blk, m)
    do i = 1, 16   ! big-endian words: the bytes of a little-endian load swapped
       x = iand(int(m(i), int64), MASK32)
       if (LITTLE_ENDIAN) x = ior(ior(shiftl(iand(x, 255_int64), 24), shiftl(iand(shiftr(x, 8), 255_int64), 16)), &
            ior(shiftl(iand(shiftr(x, 16), 255_int64), 8), shiftr(x, 24)))
       w(i) = x
    end do
    do i = 17, 64
       s0 = ieor(ieor(rotr(w(i - 15), 7), rotr(w(i - 15), 18)), shiftr(w(i - 15), 3))
       s1 = ieor(ieor(rotr(w(i - 2), 17), rotr(w(i - 2), 19)), shiftr(w(i - 2), 10))
       w(i) = iand(w(i - 16) + s0 + w(i - 7) + s1, MASK32)
    end do
    a = h
    do i = 1, 64
       s1 = ieor(ieor(rotr(a(5), 6), rotr(a(5), 11)), rotr(a(5), 25))
       ch = ieor(a(7), iand(a(5), ieor(a(6), a(7))))          ! (e and f) xor (not e and g)
       t1 = a(8) + s1 + ch + K(i) + w(i)                       ! masked where stored
       s0 = ieor(ieor(rotr(a(1), 2), rotr(a(1), 13)), rotr(a(1), 22))
       maj = ior(iand(a(1), ior(a(2), a(3))), iand(a(2), a(3)))  ! majority of a, b, c
       t2 = s0 + maj
       a(2:8) = a(1:7)
       a(5) = iand(a(5) + t1, MASK32)
       a(1) = iand(t1 + t2, MASK32)
    end do
    h = iand(h + a, MASK32)
  end subroutine compress
end module superjoin_utils_sha256
